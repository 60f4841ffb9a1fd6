#include "gl/gpu_timer.h"

#include <cstdint>

#include "gl/gl_api.h"

namespace photovr::gl {

GpuTimer::GpuTimer() {
  api::CreateQueries(GL_TIME_ELAPSED, 1, &query_);
}

GpuTimer::~GpuTimer() {
  api::DeleteQueries(1, &query_);
}

void GpuTimer::begin() {
  api::BeginQuery(GL_TIME_ELAPSED, query_);
}

void GpuTimer::end() {
  api::EndQuery(GL_TIME_ELAPSED);
}

double GpuTimer::ms() const {
  uint64_t ns = 0;
  api::GetQueryObjectui64v(query_, GL_QUERY_RESULT, &ns);
  return double(ns) * 1e-6;
}

}  // namespace photovr::gl
