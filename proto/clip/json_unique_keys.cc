#include "proto/clip/json_unique_keys.h"

#include <nlohmann/json.hpp>
#include <set>
#include <vector>

namespace reenact::proto {

namespace {

using nlohmann::json;

// Walks the document's events with a stack of the open objects and arrays; stops at the first
// key its object already has.
class DuplicateKeyFinder : public nlohmann::json_sax<json> {
 public:
  const std::optional<std::string>& found() const { return found_; }

  bool null() override { return Scalar(); }
  bool boolean(bool) override { return Scalar(); }
  bool number_integer(number_integer_t) override { return Scalar(); }
  bool number_unsigned(number_unsigned_t) override { return Scalar(); }
  bool number_float(number_float_t, const string_t&) override { return Scalar(); }
  bool string(string_t&) override { return Scalar(); }
  bool binary(binary_t&) override { return Scalar(); }

  bool start_object(std::size_t) override {
    Open open;
    open.path = ChildPath();
    stack_.push_back(std::move(open));
    return true;
  }
  bool key(string_t& key) override {
    Open& object = stack_.back();
    if (!object.keys.insert(key).second) {
      found_ = Join(object.path, key);
      return false;  // stops the parse
    }
    object.key = key;
    return true;
  }
  bool end_object() override { return Close(); }

  bool start_array(std::size_t) override {
    Open open;
    open.path = ChildPath();
    open.is_array = true;
    stack_.push_back(std::move(open));
    return true;
  }
  bool end_array() override { return Close(); }

  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
    return false;
  }

 private:
  // An object or array not yet closed.
  struct Open {
    std::string path;  // of the object or array itself; "" for the root
    bool is_array = false;
    size_t next_index = 0;       // array: index of the next element
    std::set<std::string> keys;  // object: its keys so far
    std::string key;             // object: the key of the value being read
  };

  static std::string Join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

  // The path of the value that starts now; moves an array on to its next element.
  std::string ChildPath() {
    if (stack_.empty()) return "";
    Open& parent = stack_.back();
    if (parent.is_array) return parent.path + "[" + std::to_string(parent.next_index++) + "]";
    return Join(parent.path, parent.key);
  }

  bool Scalar() {
    if (!stack_.empty() && stack_.back().is_array) ++stack_.back().next_index;
    return true;
  }

  bool Close() {
    stack_.pop_back();
    return true;
  }

  std::vector<Open> stack_;
  std::optional<std::string> found_;
};

}  // namespace

std::optional<std::string> FirstDuplicateKey(std::string_view json_text) {
  DuplicateKeyFinder finder;
  json::sax_parse(json_text, &finder);
  return finder.found();
}

}  // namespace reenact::proto
