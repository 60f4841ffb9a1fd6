// An explicit, ordered list of GL passes, each declaring the resources it reads and writes
// (the idea of Falcor's RenderPass::reflect() and Filament's frame
// graph, without their allocation: resources are names, and the owner of the list maps
// each to its texture, ping-pong included). Built once by the owner; the declarations are
// checked when the list is made, so a pass moved before what it reads fails at once, with
// its name, instead of reading last frame's texels.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace photovr::gl {

struct PassTiming {
  std::string name;
  double ms;  // glFinish-bracketed wall time
};

struct PassDecl {
  std::string name;  // also its timing's; need not be unique (the a-trous iterations)
  std::vector<std::string> reads, writes;
  std::function<void()> execute;
};

class PassList {
 public:
  PassList() = default;  // no passes
  // Throws std::logic_error, naming the pass (index and name) and the resource, when a pass
  // reads what is neither one of 'inputs' nor written by an earlier pass, when one of
  // 'outputs' is written by no pass, or when a pass has nothing to execute.
  PassList(std::vector<std::string> inputs, std::vector<std::string> outputs,
           std::vector<PassDecl> passes);

  // The passes in order; with 'timings', each bracketed by glFinish and its time appended
  // (a pass that throws appends nothing).
  void run(std::vector<PassTiming>* timings = nullptr) const;

  const std::vector<PassDecl>& passes() const { return passes_; }
  const std::vector<std::string>& inputs() const { return inputs_; }
  const std::vector<std::string>& outputs() const { return outputs_; }
  // Index of the last pass before 'before' that writes 'resource'; -1 for none.
  int writer(const std::string& resource, size_t before) const;
  // Indices of the passes named 'name', in order.
  std::vector<size_t> find(const std::string& name) const;

 private:
  void validate() const;

  std::vector<std::string> inputs_, outputs_;
  std::vector<PassDecl> passes_;
};

}  // namespace photovr::gl
