#include "harness/reference_shards.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/error_metrics.h"
#include "core/files.h"

namespace photovr::harness {
namespace {

namespace fs = std::filesystem;

// Fixed point: values x 2^32. Frame values (4-spp means of radiance) are clamped to
// +-2^31 first so that one term fits in 63 bits; 2^24 such terms (the most frames a
// reference has) stay below 2^87 in the 127 bits of the sums. Squares are clamped the same
// way (values above 46341): that caps only the error estimate of a pixel with such a
// firefly, never the mean. A step of 2^-32 (2.3e-10) is far below what a reference resolves.
constexpr double kScale = 4294967296.0;  // 2^32
constexpr double kClamp = 2147483648.0;  // 2^31

__int128 fixedPoint(double v) {
  if (!std::isfinite(v)) return 0;  // the tracer drops NaN/Inf samples; never seen here
  return __int128(std::llround(std::clamp(v, -kClamp, kClamp) * kScale));
}

const char* const kMagic = "photovr-shard-1";

std::string header(const ShardSums& s) {
  std::ostringstream h;
  h << kMagic << ' ' << s.id.index << ' ' << s.id.count << ' ' << s.width << ' ' << s.height << ' '
    << s.eyes << ' ' << s.frames << '\n';
  return h.str();
}

size_t valuesOf(int width, int height, int eyes) {
  return size_t(width) * size_t(height) * size_t(eyes) * 3;
}

}  // namespace

ShardId parseShard(const std::string& text) {
  ShardId id;
  char slash = 0;
  std::istringstream in(text);
  if (!(in >> id.index >> slash >> id.count) || slash != '/' || !in.eof() || id.count < 1 ||
      id.count > 4096 || id.index < 0 || id.index >= id.count)
    throw UsageError("--shard: expected K/N with 0 <= K < N <= 4096, got '" + text + "'");
  return id;
}

int framesOfShard(const ShardId& id, int totalFrames) {
  return totalFrames > id.index ? (totalFrames - id.index + id.count - 1) / id.count : 0;
}

ShardSums::ShardSums(ShardId shard, int w, int h, int e)
    : id(shard),
      width(w),
      height(h),
      eyes(e),
      sum(valuesOf(w, h, e), 0),
      sumOfSquares(valuesOf(w, h, e), 0) {}

void ShardSums::add(int eye, const std::vector<glm::vec3>& values) {
  const size_t base = size_t(eye) * size_t(width) * size_t(height) * 3;
  for (size_t i = 0; i < values.size() && base + 3 * i + 2 < sum.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double v = values[i][c];
      sum[base + 3 * i + size_t(c)] += fixedPoint(v);
      sumOfSquares[base + 3 * i + size_t(c)] += fixedPoint(v * v);
    }
}

std::string shardFile(const std::string& directory, const ShardId& id) {
  return directory + "/shard-" + std::to_string(id.index) + "-of-" + std::to_string(id.count) +
         ".bin";
}

void saveShard(const std::string& directory, const ShardSums& s) {
  std::string bytes = header(s);
  const size_t payload = s.sum.size() * sizeof(__int128);
  const size_t at = bytes.size();
  bytes.resize(at + 2 * payload);
  std::memcpy(bytes.data() + at, s.sum.data(), payload);
  std::memcpy(bytes.data() + at + payload, s.sumOfSquares.data(), payload);
  writeFileAtomically(shardFile(directory, s.id), bytes);
}

std::optional<ShardSums> loadShard(const std::string& directory, const ShardId& id, int width,
                                   int height, int eyes) {
  std::ifstream in(shardFile(directory, id), std::ios::binary);
  if (!in) return std::nullopt;
  std::string line;
  std::getline(in, line);
  ShardSums s(id, width, height, eyes);
  std::istringstream h(line);
  std::string magic;
  ShardId stored;
  int w = 0, ht = 0, e = 0, frames = -1;
  if (!(h >> magic >> stored.index >> stored.count >> w >> ht >> e >> frames) || magic != kMagic ||
      stored.index != id.index || stored.count != id.count || w != width || ht != height ||
      e != eyes || frames < 0 || frames > (1 << 24))
    return std::nullopt;
  const std::string rest((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t payload = s.sum.size() * sizeof(__int128);
  if (rest.size() != 2 * payload) return std::nullopt;
  std::memcpy(s.sum.data(), rest.data(), payload);
  std::memcpy(s.sumOfSquares.data(), rest.data() + payload, payload);
  s.frames = frames;
  return s;
}

std::optional<MergedReference> mergeShards(const std::string& directory, int count, int width,
                                           int height, int eyes) {
  std::vector<ShardSums> shards;
  int total = 0;
  for (int k = 0; k < count; ++k) {
    std::optional<ShardSums> s = loadShard(directory, {k, count}, width, height, eyes);
    if (!s) return std::nullopt;
    total += s->frames;
    shards.push_back(std::move(*s));
  }
  for (const ShardSums& s : shards)  // together exactly frames [0, total)
    if (s.frames != framesOfShard(s.id, total)) return std::nullopt;
  if (total == 0) return std::nullopt;
  std::vector<__int128> sum(valuesOf(width, height, eyes), 0), squares = sum;
  for (const ShardSums& s : shards)
    for (size_t i = 0; i < sum.size(); ++i) {
      sum[i] += s.sum[i];
      squares[i] += s.sumOfSquares[i];
    }
  MergedReference m;
  m.frames = total;
  const size_t pixels = size_t(width) * size_t(height);
  double relMse = 0.0;
  for (int e = 0; e < eyes; ++e) {
    std::vector<glm::vec3> mean(pixels);
    for (size_t p = 0; p < pixels; ++p)
      for (int c = 0; c < 3; ++c) {
        const size_t i = (size_t(e) * pixels + p) * 3 + size_t(c);
        const double mu = double(sum[i]) / kScale / total;
        const double second = double(squares[i]) / kScale / total;
        const double varianceOfMean = std::max(0.0, second - mu * mu) / total;
        mean[p][c] = float(mu);
        relMse += varianceOfMean / (mu * mu + double(kRelMseEpsilon));
      }
    m.eyes.push_back(std::move(mean));
  }
  m.estimatedRelMse = relMse / double(std::max<size_t>(1, pixels * size_t(eyes) * 3));
  return m;
}

std::vector<int> shardCountsIn(const std::string& directory) {
  std::set<int> counts;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(directory, ec)) {
    const std::string name = entry.path().filename().string();
    int k = 0, n = 0;
    if (std::sscanf(name.c_str(), "shard-%d-of-%d.bin", &k, &n) == 2 && n >= 1) counts.insert(n);
  }
  return {counts.begin(), counts.end()};
}

}  // namespace photovr::harness
