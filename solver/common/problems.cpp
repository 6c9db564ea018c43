#include "solver/common/problems.h"

namespace simsols {

namespace {

std::string detail(const FileProblem& p) {
  return (p.field.empty() ? std::string() : "field '" + p.field + "': ") + p.message;
}

}  // namespace

std::string describe_problems(const std::string& file, const std::vector<FileProblem>& all) {
  std::string s = file.empty() ? std::string("<scene>") : file;
  if (all.size() == 1) {
    if (all[0].line > 0) s += ":" + std::to_string(all[0].line);
    return s + ": " + detail(all[0]);
  }
  s += ": " + std::to_string(all.size()) + " problems:";
  for (const FileProblem& p : all)
    s += "\n  " + (p.line > 0 ? "line " + std::to_string(p.line) + ": " : std::string()) +
         detail(p);
  return s;
}

}  // namespace simsols
