#include "capture-client/skeleton/skeleton_track_spec.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "capture-client/skeleton/kinect_v1_skeleton.h"
#include "capture-client/skeleton/skeleton_track_json.h"
#include "capture-client/source/source_argument.h"

namespace reenact::capture {
namespace {

constexpr std::string_view kAccepted =
    "accepted: json:FILE, kinect:FILE (UTKinect joints_sXX_eYY.txt, MSR Action3D "
    "aXX_sYY_eZZ_skeleton3D.txt, MSR DailyActivity3D aXX_sYY_eZZ_skeleton.txt, UTD-MHAD "
    "skeleton.txt) or FILE.json, "
    "each optionally with ?frame_offset=N&time_offset_s=S&tolerance_s=S";

bool EndsWithJson(std::string_view s) {
  if (s.size() < 5) return false;
  std::string tail(s.substr(s.size() - 5));
  for (char& c : tail) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return tail == ".json";
}

Expected<double> ParseSeconds(std::string_view kind, const std::string& name,
                              const std::string& value, bool non_negative) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v) ||
      (non_negative && v < 0))
    return MakeError("usage",
                     std::string(kind) + ": " + name + "=" + value + " must be " +
                         (non_negative ? "a number of seconds >= 0" : "a number of seconds"));
  return v;
}

Expected<SkeletonTrackLookupOptions> ParseLookup(std::string_view kind,
                                                 const SourceArgument& argument) {
  SkeletonTrackLookupOptions lookup;
  const auto& options = argument.options;
  if (const auto it = options.find("frame_offset"); it != options.end()) {
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(it->second.c_str(), &end, 10);
    if (it->second.empty() || *end != '\0' || errno == ERANGE)
      return MakeError("usage", std::string(kind) + ": frame_offset=" + it->second +
                                    " must be an integer (track index = captured index + N)");
    lookup.frame_index_offset = v;
  }
  if (const auto it = options.find("time_offset_s"); it != options.end()) {
    Expected<double> v = ParseSeconds(kind, "time_offset_s", it->second, false);
    if (!v.ok()) return v.error();
    lookup.timestamp_offset_s = *v;
  }
  if (const auto it = options.find("tolerance_s"); it != options.end()) {
    Expected<double> v = ParseSeconds(kind, "tolerance_s", it->second, true);
    if (!v.ok()) return v.error();
    lookup.timestamp_tolerance_s = *v;
  }
  return lookup;
}

Expected<SourceArgument> ParseWithPath(std::string_view kind, std::string_view argument,
                                       std::initializer_list<std::string_view> known) {
  Expected<SourceArgument> parsed = ParseSourceArgument(kind, argument, known);
  if (!parsed.ok()) return parsed.error();
  if (parsed->path.empty())
    return MakeError("usage", "--skeleton " + std::string(kind) + ": needs a file, e.g. " +
                                  std::string(kind) + ":track.txt; " + std::string(kAccepted));
  return parsed;
}

}  // namespace

Expected<SkeletonTrack> LoadSkeletonTrack(const std::string& spec) {
  const std::string_view s = spec;
  if (s.starts_with("json:")) {
    Expected<SourceArgument> arg =
        ParseWithPath("json", s.substr(5), {"frame_offset", "time_offset_s", "tolerance_s"});
    if (!arg.ok()) return arg.error();
    Expected<SkeletonTrackLookupOptions> lookup = ParseLookup("json", *arg);
    if (!lookup.ok()) return lookup.error();
    return ReadSkeletonTrackJson(arg->path, *lookup);
  }
  if (s.starts_with("kinect:")) {
    Expected<SourceArgument> arg = ParseWithPath(
        "kinect", s.substr(7), {"frame_offset", "time_offset_s", "tolerance_s", "variant"});
    if (!arg.ok()) return arg.error();
    KinectV1ReadOptions options;
    Expected<SkeletonTrackLookupOptions> lookup = ParseLookup("kinect", *arg);
    if (!lookup.ok()) return lookup.error();
    options.lookup = *lookup;
    if (const auto it = arg->options.find("variant"); it != arg->options.end()) {
      const std::optional<KinectTextVariant> variant = KinectTextVariantFromName(it->second);
      if (!variant)
        return MakeError("usage",
                         "kinect: variant=" + it->second +
                             " is not one of utkinect, msr-action3d, msr-daily, utd-mhad, detect");
      options.variant = *variant;
    }
    return ReadKinectV1SkeletonTrack(arg->path, options);
  }
  if (EndsWithJson(s)) return ReadSkeletonTrackJson(spec);
  return MakeError("usage",
                   "--skeleton " + spec + ": unknown skeleton source; " + std::string(kAccepted));
}

}  // namespace reenact::capture
