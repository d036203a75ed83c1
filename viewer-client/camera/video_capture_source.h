#pragma once
// A video file or a live camera through OpenCV's VideoCapture (FFmpeg for files, V4L2 for
// cameras on Linux). Frames are converted to RGB and must have the calibration's size.

#include <filesystem>
#include <memory>

#include "viewer-client/camera/camera_source.h"

namespace reenact::viewer {

// Errors: "not_found" (no such file), "unsupported" (no decoder opens it, or its first frame
// cannot be read).
Expected<std::unique_ptr<CameraSource>> OpenVideoFileSource(const std::filesystem::path& file,
                                                            const PinholeCamera& camera);

// Errors: "unavailable" when camera `index` cannot be opened (none attached, or no access)
// or delivers no frame.
Expected<std::unique_ptr<CameraSource>> OpenLiveCameraSource(int index,
                                                             const PinholeCamera& camera);

}  // namespace reenact::viewer
