#pragma once
// `reenact-bench viewer`: how fast the viewer draws and runs its AR loop at 640x480 on the
// machine's OpenGL (Mesa llvmpipe where there is no GPU), issue 7's speed goals.
//
//   reenact-bench viewer [--frames N] [--repeats R] [--texturing NAME] [--json FILE]
//
// --texturing: the reenactment's texturing preset (viewer-client/play/texturing_presets.h),
// default the viewer's (kDefaultTexturingPreset); issue 9's goal is the whole loop at 30 fps or
// more with its methods too.
//
// Set-up (not timed): turn-and-kick's first 60 frames are recorded through the real capture
// path and read back (clip and relocalisation map); the synthetic viewer camera
// (viewer-client/camera/synthetic_camera_source.h: 0 -> +45 -> 0 -> -45 -> 0 degrees around
// the capture viewpoint, the room alone) delivers N frames (default 60), rendered once before
// timing so that the scene's CPU rasteriser is not counted as the camera (its time is the
// source_ms of the camera rows: a real camera delivers frames without it). The same frames
// are also written as a TUM directory and read back through the `tum:` camera (PNG decoding
// counted), the case of a recorded camera.
//
// Rows, each measured R times (default 3) over the whole sequence: stage times (source_ms,
// reloc_ms, select_ms, render_ms, composite_ms; ms_per_frame for a whole loop) are medians
// over every frame of every run; fps is the median over runs of frames / the run's wall time;
// x_thesis, x_cpu, x_orbit_loop and x_sequential divide fps by the thesis's, the CPU
// reference's, the orbit loop's and the sequential AR loop's:
//   thesis            9 fps on a Surface Pro 2 (the reference row; THESIS.md)
//   cpu-reference     the CPU reference renderer (common/render/reference_renderer.h) on the
//                     orbit viewpoint's draws: the baseline of x_cpu
//   render-orbit      GL draw + read-back of prepared draw lists, orbit viewpoint (60 degrees)
//                     over the floor grid: render only
//   render-ar         the same over the camera image at the camera's true poses
//   loop-orbit        texture selection (Reenactment::Build) + draw + read-back, orbit
//   loop-ar-synthetic the whole AR loop as the viewer runs it (ArPipeline, ar_pipeline.h):
//                     relocalise or track camera frame i + 1 on a worker while frame i is
//                     composed (select, draw over the camera image + read-back, banner);
//                     ms_per_frame is a frame's own time, frames overlap
//   loop-ar-tum       the same with the camera's frames read from disk (tum:DIR)
//   loop-ar-sequential ArCompositor::Process per camera frame, one step after the other: the
//                     baseline of x_sequential
// Goals (issue 7): render-only >= 60 fps, whole loop >= 30 fps.

#include "common/cli/command_line.h"

namespace reenact::bench {

int RunViewerBench(const CommandLine& cl);

}  // namespace reenact::bench
