#pragma once
// The results of `reenact-eval quality` for people: the report of DESIGN.md (table on stdout,
// --json FILE with the field names psnr_db, ssim, iou, wrong_part_rate, ms_per_frame, ...)
// and a markdown document (--markdown FILE; `make eval` writes docs/quality.md) with the
// table, the measurement rules, the machine and the side-by-side pictures.

#include <string>

#include "common/error/expected.h"
#include "proto/report/report_table.h"
#include "tests/eval/quality_eval.h"

namespace reenact::eval {

// One row per method and view.
proto::Report QualityReport(const QualityRun& run);

// The rules behind the figures, one line each (crop rule, wrong-part rule, provenance,
// timing), printed under the table and written into the markdown.
std::vector<std::string> QualityRules();

// Why the clip has fewer frames than the scenario (the tracker lost some), as a clause; empty
// when it has them all.
std::string LostFramesNote(const QualityRun& run);

// One sentence on the fitted subject light against the scene's: strength, the angle between
// them, the fit's gain; or why none was found.
std::string SubjectLightLine(const QualityRun& run);

// The part surfaces fitted at load (surface_fit.h): each part's chosen number of angles, the
// held-out error of the rings alone and of the chosen resolution (mean over parts weighted by
// their points, millimetres), and the body model's size: extensions, rings and surface nodes
// as 4-byte floats (fitted at load from the stored frames, so nothing is added to the clip).
std::string SurfaceFitLine(const QualityRun& run);

// The reenact-eval command line that reproduces the options' figures.
std::string QualityCommandLine(const QualityOptions& options);

// "YYYY-MM-DD (UTC), CPU model, N logical cores, OpenGL renderer R": when and where.
std::string MachineLine(const std::string& gl_renderer);

// The markdown document; image links relative to the document's folder (markdown_path).
std::string QualityMarkdown(const QualityOptions& options, const QualityRun& run,
                            const std::string& markdown_path, const std::string& machine_line);

// Writes text to path (replacing it). Error "io" naming the path.
Status WriteTextFile(const std::string& path, const std::string& text);

}  // namespace reenact::eval
