// The CPU half of a hybrid frame: each visible pixel of a G-buffer is rebuilt exactly and
// its paths continued by the tracer's own batched tracer (trace/wavefront.h), identical in
// expectation to pure path tracing with the same camera and jitter.
#pragma once

#include <cstdint>
#include <vector>

#include "core/camera.h"
#include "gl/gbuffer.h"
#include "hybrid/hit_rebuild.h"
#include "trace/path_tracer.h"
#include "trace/sample_map.h"

namespace photovr {

struct HybridEyeStats {
  double rebuildMs = 0.0;     // visibility record -> exact surface hit
  double traceMs = 0.0;       // the paths of all samples (wavefront tracer)
  uint64_t outsideHits = 0;   // shared-edge raster/ray disagreements, clamped and counted
  uint64_t tracedPixels = 0;  // pixels with samples > 0 that saw a surface
  // With the 'sky-pixels' skip off: background pixels whose Embree ray hit a surface
  // (silhouette pixels where raster and ray disagree; the pixel still shows the sky).
  uint64_t skyRayHits = 0;
};

// 'samples': per-pixel sample counts (trace/sample_map.h; uniform = ctx.settings' count).
// Fills color, the AOVs and the demodulated diffuse/specular denoiser inputs.
//
// 'reuse': storage kept from frame to frame, or null. The traced image is built in
// reuse->image (give the returned image back there when done with it): at 960x1080 it and
// the rebuilt hits the tracer then kept per image were ~190 MB per eye, whose first touch as
// fresh memory cost ~640 ms per eye here (docs/ARCHITECTURE.md, "Memory reuse"); the hits
// are now rebuilt a tile at a time into a buffer each thread keeps.
// 'stereo': this eye's part in stereo path reuse (trace/stereo_reuse.h).
struct HybridEyeBuffers {
  EyeImage image;
};
EyeImage traceFromGBuffer(const TraceContext& ctx, const gl::GBufferImage& gbuffer,
                          const EyeCamera& camera, uint32_t eye, uint32_t frame,
                          const SampleMap& samples, HybridEyeStats* stats,
                          HybridEyeBuffers* reuse = nullptr, StereoRole stereo = {});

}  // namespace photovr
