#include "gl/pass_list.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <utility>

#include "gl/gl_api.h"

namespace photovr::gl {
namespace {

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::string passName(size_t index, const PassDecl& pass) {
  return "pass " + std::to_string(index) + " '" + pass.name + "'";
}

}  // namespace

PassList::PassList(std::vector<std::string> inputs, std::vector<std::string> outputs,
                   std::vector<PassDecl> passes)
    : inputs_(std::move(inputs)), outputs_(std::move(outputs)), passes_(std::move(passes)) {
  validate();
}

void PassList::validate() const {
  for (size_t i = 0; i < passes_.size(); ++i) {
    if (!passes_[i].execute) throw std::logic_error(passName(i, passes_[i]) + " executes nothing");
    for (const std::string& r : passes_[i].reads)
      if (!contains(inputs_, r) && writer(r, i) < 0)
        throw std::logic_error(passName(i, passes_[i]) + " reads '" + r +
                               "', which is neither an input nor written by an earlier pass");
  }
  for (const std::string& o : outputs_)
    if (writer(o, passes_.size()) < 0)
      throw std::logic_error("output '" + o + "' is written by no pass");
}

int PassList::writer(const std::string& resource, size_t before) const {
  for (size_t i = std::min(before, passes_.size()); i-- > 0;)
    if (contains(passes_[i].writes, resource)) return int(i);
  return -1;
}

std::vector<size_t> PassList::find(const std::string& name) const {
  std::vector<size_t> found;
  for (size_t i = 0; i < passes_.size(); ++i)
    if (passes_[i].name == name) found.push_back(i);
  return found;
}

void PassList::run(std::vector<PassTiming>* timings) const {
  for (const PassDecl& pass : passes_) {
    if (!timings) {
      pass.execute();
      continue;
    }
    api::Finish();
    const auto t0 = std::chrono::steady_clock::now();
    pass.execute();
    api::Finish();
    const std::chrono::duration<double, std::milli> ms = std::chrono::steady_clock::now() - t0;
    timings->push_back({pass.name, ms.count()});
  }
}

}  // namespace photovr::gl
