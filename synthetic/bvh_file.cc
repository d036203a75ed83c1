#include "synthetic/bvh_file.h"

#include <charconv>
#include <cmath>
#include <numbers>
#include <optional>

#include "common/error/check.h"
#include "common/io/text_file.h"

namespace reenact::capture {
namespace {

constexpr int kMaxDepth = 256;  // nesting guard for hostile input

struct Token {
  std::string_view text;
  int line = 0;  // 1-based
};

std::vector<std::string_view> SplitLines(std::string_view text) {
  std::vector<std::string_view> lines;
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    start = end + 1;
  }
  return lines;
}

bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f'; }

// Splits one line into whitespace-separated tokens; braces are tokens of their own.
void AppendTokens(std::string_view line, int line_number, std::vector<Token>* out) {
  size_t i = 0;
  while (i < line.size()) {
    if (IsSpace(line[i])) {
      ++i;
      continue;
    }
    if (line[i] == '{' || line[i] == '}') {
      out->push_back({line.substr(i, 1), line_number});
      ++i;
      continue;
    }
    size_t j = i;
    while (j < line.size() && !IsSpace(line[j]) && line[j] != '{' && line[j] != '}') ++j;
    out->push_back({line.substr(i, j - i), line_number});
    i = j;
  }
}

std::optional<double> ParseDouble(std::string_view s) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::optional<BvhChannel> ParseChannel(std::string_view s) {
  if (s == "Xposition") return BvhChannel::kXposition;
  if (s == "Yposition") return BvhChannel::kYposition;
  if (s == "Zposition") return BvhChannel::kZposition;
  if (s == "Xrotation") return BvhChannel::kXrotation;
  if (s == "Yrotation") return BvhChannel::kYrotation;
  if (s == "Zrotation") return BvhChannel::kZrotation;
  return std::nullopt;
}

class Parser {
 public:
  Parser(std::string_view text, std::string_view source) : source_(source) {
    lines_ = SplitLines(text);
  }

  Expected<BvhClip> Parse() {
    // Tokenise the hierarchy up to and including the MOTION keyword.
    size_t line = 0;
    for (; line < lines_.size() && !motion_token_; ++line) {
      const size_t before = tokens_.size();
      AppendTokens(lines_[line], static_cast<int>(line) + 1, &tokens_);
      for (size_t k = before; k < tokens_.size(); ++k)
        if (tokens_[k].text == "MOTION") {
          motion_token_ = k;
          break;
        }
    }
    if (!motion_token_)
      return Fail(static_cast<int>(lines_.size()),
                  "no MOTION section: the file ends inside the hierarchy (truncated?)");
    tokens_.resize(*motion_token_ + 1);
    if (Status s = ParseHierarchy(); !s.ok()) return s.error();
    if (Status s = ParseMotion(); !s.ok()) return s.error();
    return std::move(clip_);
  }

 private:
  Error Fail(int line, const std::string& what) const {
    return MakeError("corrupt", std::string(source_) + ":" + std::to_string(line) + ": " + what);
  }
  int LastLine() const { return tokens_.empty() ? 1 : tokens_.back().line; }

  std::optional<Token> Next() {
    if (pos_ >= tokens_.size()) return std::nullopt;
    return tokens_[pos_++];
  }
  const Token* Peek() const { return pos_ < tokens_.size() ? &tokens_[pos_] : nullptr; }

  Status Expect(std::string_view keyword, std::string_view context) {
    const std::optional<Token> t = Next();
    if (!t)
      return Fail(LastLine(), "expected '" + std::string(keyword) + "' " + std::string(context) +
                                  ", found the end of the file");
    if (t->text != keyword)
      return Fail(t->line, "expected '" + std::string(keyword) + "' " + std::string(context) +
                               ", found '" + std::string(t->text) + "'");
    return {};
  }

  Expected<double> Number(std::string_view what) {
    const std::optional<Token> t = Next();
    if (!t) return Fail(LastLine(), "expected " + std::string(what) + ", found the end");
    const std::optional<double> v = ParseDouble(t->text);
    if (!v) {
      std::string message = "'";  // built in steps: GCC 12 misreports -Wrestrict on "'" + ...
      message.append(t->text).append("' is not a finite number (").append(what).append(")");
      return Fail(t->line, message);
    }
    return *v;
  }

  Status ParseHierarchy() {
    if (Status s = Expect("HIERARCHY", "at the start of the file"); !s.ok()) return s;
    while (Peek() && Peek()->text == "ROOT") {
      const Token root = *Next();
      if (Status s = ParseJoint(root, -1, 0); !s.ok()) return s;
    }
    const std::optional<Token> t = Next();
    if (clip_.joints.empty())
      return Fail(t ? t->line : LastLine(),
                  "expected 'ROOT' after HIERARCHY, found '" + std::string(t ? t->text : "") + "'");
    if (!t || t->text != "MOTION")
      return Fail(t ? t->line : LastLine(),
                  "expected 'ROOT' or 'MOTION' after a joint block, found '" +
                      std::string(t ? t->text : "") + "'");
    return {};
  }

  // Parses a ROOT or JOINT block whose keyword is `keyword` (the name follows on its line).
  Status ParseJoint(const Token& keyword, int parent, int depth) {
    if (depth > kMaxDepth) return Fail(keyword.line, "joints nested too deeply");
    BvhJoint joint;
    joint.parent = parent;
    joint.line = keyword.line;
    std::string name;
    while (Peek() && Peek()->line == keyword.line && Peek()->text != "{") {
      if (!name.empty()) name += ' ';
      name += Next()->text;
    }
    if (name.empty())
      return Fail(keyword.line, std::string(keyword.text) + " without a joint name");
    joint.name = name;
    const std::string context = "in joint '" + name + "'";
    if (Status s = Expect("{", "after " + std::string(keyword.text) + " " + name); !s.ok())
      return s;
    if (Status s = Expect("OFFSET", context); !s.ok()) return s;
    for (int k = 0; k < 3; ++k) {
      Expected<double> v = Number("OFFSET coordinate " + context);
      if (!v.ok()) return v.error();
      joint.offset[k] = *v;
    }
    if (Status s = Expect("CHANNELS", context); !s.ok()) return s;
    const std::optional<Token> count_token = Next();
    int count = -1;
    if (count_token) {
      const std::string_view c = count_token->text;
      const auto [end, ec] = std::from_chars(c.data(), c.data() + c.size(), count);
      if (ec != std::errc() || end != c.data() + c.size()) count = -1;
    }
    if (count < 0 || count > 6)
      return Fail(count_token ? count_token->line : LastLine(),
                  "CHANNELS count must be an integer in [0, 6] " + context);
    const int channels_line = count_token->line;
    while (Peek() && Peek()->line == channels_line) {
      const Token t = *Next();
      const std::optional<BvhChannel> c = ParseChannel(t.text);
      if (!c)
        return Fail(t.line, "unknown channel '" + std::string(t.text) + "' " + context +
                                " (expected X/Y/Z followed by position or rotation)");
      for (BvhChannel seen : joint.channels)
        if (seen == *c)
          return Fail(t.line, "channel '" + std::string(t.text) + "' listed twice " + context);
      joint.channels.push_back(*c);
    }
    if (static_cast<int>(joint.channels.size()) != count)
      return Fail(channels_line, "CHANNELS declares " + std::to_string(count) +
                                     " channels but lists " +
                                     std::to_string(joint.channels.size()) + " " + context);
    joint.first_channel = clip_.channel_count;
    clip_.channel_count += count;
    const int self = static_cast<int>(clip_.joints.size());
    clip_.joints.push_back(std::move(joint));

    while (true) {
      const std::optional<Token> t = Next();
      if (!t) return Fail(LastLine(), "'}' missing for joint '" + name + "'");
      if (t->text == "}") return {};
      if (t->text == "JOINT") {
        if (Status s = ParseJoint(*t, self, depth + 1); !s.ok()) return s;
      } else if (t->text == "End") {
        if (Status s = ParseEndSite(*t, self); !s.ok()) return s;
      } else {
        return Fail(t->line, "expected 'JOINT', 'End Site' or '}' " + context + ", found '" +
                                 std::string(t->text) + "'");
      }
    }
  }

  Status ParseEndSite(const Token& end, int parent) {
    const std::string context = "in the End Site of '" + clip_.joints[parent].name + "'";
    if (Status s = Expect("Site", "after 'End'"); !s.ok()) return s;
    if (Status s = Expect("{", context); !s.ok()) return s;
    if (Status s = Expect("OFFSET", context); !s.ok()) return s;
    BvhJoint site;
    site.name = clip_.joints[parent].name + "/End Site";
    site.parent = parent;
    site.end_site = true;
    site.line = end.line;
    site.first_channel = clip_.channel_count;
    for (int k = 0; k < 3; ++k) {
      Expected<double> v = Number("OFFSET coordinate " + context);
      if (!v.ok()) return v.error();
      site.offset[k] = *v;
    }
    if (Status s = Expect("}", context); !s.ok()) return s;
    clip_.joints.push_back(std::move(site));
    return {};
  }

  // The MOTION header is read token by token from the MOTION line on; frames line by line.
  Status ParseMotion() {
    const int motion_line = tokens_.back().line;
    std::vector<Token> header;
    size_t line = motion_line;  // 0-based index of the line after MOTION
    {
      // Any tokens after MOTION on its own line belong to the header too.
      std::vector<Token> on_motion_line;
      AppendTokens(lines_[motion_line - 1], motion_line, &on_motion_line);
      bool after = false;
      for (const Token& t : on_motion_line) {
        if (after) header.push_back(t);
        if (t.text == "MOTION") after = true;
      }
    }
    // "Frames: N" and "Frame Time: T" take 5 tokens.
    while (header.size() < 5 && line < lines_.size()) {
      AppendTokens(lines_[line], static_cast<int>(line) + 1, &header);
      ++line;
    }
    auto at = [&](size_t k) -> std::string_view {
      return k < header.size() ? header[k].text : std::string_view();
    };
    auto line_of = [&](size_t k) {
      return k < header.size() ? header[k].line : static_cast<int>(lines_.size());
    };
    if (at(0) != "Frames:")
      return Fail(line_of(0),
                  "expected 'Frames: N' after MOTION, found '" + std::string(at(0)) + "'");
    int frames = 0;
    {
      const std::string_view c = at(1);
      const auto [end, ec] = std::from_chars(c.data(), c.data() + c.size(), frames);
      if (c.empty() || ec != std::errc() || end != c.data() + c.size())
        return Fail(line_of(1), "'Frames:' needs an integer, found '" + std::string(c) + "'");
    }
    if (frames < 1)
      return Fail(line_of(1), "the clip has " + std::to_string(frames) +
                                  " frames; a motion needs at least one");
    if (at(2) != "Frame" || at(3) != "Time:")
      return Fail(line_of(2),
                  "expected 'Frame Time: T' after Frames, found '" + std::string(at(2)) + "'");
    const std::optional<double> frame_time = ParseDouble(at(4));
    if (!frame_time || *frame_time <= 0)
      return Fail(line_of(4), "'Frame Time:' needs a positive number of seconds, found '" +
                                  std::string(at(4)) + "'");
    if (header.size() > 5)
      return Fail(header[5].line,
                  "unexpected '" + std::string(header[5].text) + "' after the Frame Time value");
    clip_.frame_time_s = *frame_time;
    clip_.frames = frames;

    const size_t columns = static_cast<size_t>(clip_.channel_count);
    clip_.values.reserve(static_cast<size_t>(frames) * columns);
    std::vector<Token> row;
    int read = columns == 0 ? frames : 0;  // no channels: frame lines are empty
    for (; line < lines_.size(); ++line) {
      row.clear();
      const int number = static_cast<int>(line) + 1;
      AppendTokens(lines_[line], number, &row);
      if (row.empty()) continue;  // blank lines (e.g. at the end) are allowed
      if (read == frames)
        return Fail(number,
                    "more frame lines than 'Frames: " + std::to_string(frames) + "' declares");
      if (row.size() != columns)
        return Fail(number, "frame " + std::to_string(read) + " has " + std::to_string(row.size()) +
                                " values but the hierarchy " + "declares " +
                                std::to_string(columns) + " channels");
      for (const Token& t : row) {
        const std::optional<double> v = ParseDouble(t.text);
        if (!v)
          return Fail(number, "'" + std::string(t.text) + "' in frame " + std::to_string(read) +
                                  " is not a finite number");
        clip_.values.push_back(*v);
      }
      ++read;
    }
    if (read < frames)
      return Fail(static_cast<int>(lines_.size()),
                  "the file is truncated: 'Frames: " + std::to_string(frames) +
                      "' declares more frames than the " + std::to_string(read) +
                      " frame lines present");
    return {};
  }

  std::string_view source_;
  std::vector<std::string_view> lines_;
  std::vector<Token> tokens_;
  size_t pos_ = 0;
  std::optional<size_t> motion_token_;
  BvhClip clip_;
};

Eigen::Matrix3d AxisRotation(int axis, double degrees) {
  return Eigen::AngleAxisd(degrees * std::numbers::pi / 180.0, Eigen::Vector3d::Unit(axis))
      .toRotationMatrix();
}

}  // namespace

std::vector<int> BvhClip::NamedJoints() const {
  std::vector<int> out;
  for (size_t i = 0; i < joints.size(); ++i)
    if (!joints[i].end_site) out.push_back(static_cast<int>(i));
  return out;
}

std::vector<std::string> BvhClip::NamedJointNames() const {
  std::vector<std::string> out;
  for (int i : NamedJoints()) out.push_back(joints[i].name);
  return out;
}

Expected<BvhClip> ParseBvh(std::string_view text, std::string_view source) {
  return Parser(text, source).Parse();
}

Expected<BvhClip> ReadBvhFile(const std::filesystem::path& path) {
  const auto text = ReadTextFile(path, "BVH file");
  if (!text.ok()) return text.error();
  return ParseBvh(*text, path.string());
}

std::vector<Eigen::Isometry3d> BvhJointTransforms(const BvhClip& clip, int frame) {
  REENACT_CHECK(frame >= 0 && frame < clip.frame_count(),
                "BVH frame " + std::to_string(frame) + " out of range [0, " +
                    std::to_string(clip.frame_count()) + ")");
  const double* row = clip.values.data() + static_cast<size_t>(frame) * clip.channel_count;
  std::vector<Eigen::Isometry3d> out(clip.joints.size());
  for (size_t i = 0; i < clip.joints.size(); ++i) {
    const BvhJoint& j = clip.joints[i];
    Eigen::Isometry3d local = Eigen::Isometry3d::Identity();
    local.translation() = j.offset;
    for (size_t c = 0; c < j.channels.size(); ++c) {
      const double v = row[j.first_channel + c];
      const int axis = static_cast<int>(j.channels[c]) % 3;
      if (static_cast<int>(j.channels[c]) < 3)
        local.translation() += local.linear() * (v * Eigen::Vector3d::Unit(axis));
      else
        local.linear() = local.linear() * AxisRotation(axis, v);
    }
    out[i] = j.parent < 0 ? local : out[j.parent] * local;
  }
  return out;
}

std::vector<Eigen::Vector3d> BvhJointPositions(const BvhClip& clip, int frame) {
  const std::vector<Eigen::Isometry3d> transforms = BvhJointTransforms(clip, frame);
  std::vector<Eigen::Vector3d> out;
  out.reserve(transforms.size());
  for (const Eigen::Isometry3d& t : transforms) out.push_back(t.translation());
  return out;
}

}  // namespace reenact::capture
