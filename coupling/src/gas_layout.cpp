#include "tfdem/gas_layout.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace tfdem::gas_layout {

const char *name(Layout layout) { return layout == Layout::whole ? "whole" : "split"; }

double split_from_cells(int ranks) {
  if (ranks < 2) return -1.0;
  const double gain = kWholeStep.per_cell_seconds - kSplitStep.per_cell_seconds / ranks;
  const double overhead = kSplitStep.fixed_seconds - kWholeStep.fixed_seconds;
  if (gain <= 0) return overhead <= 0 ? 0.0 : -1.0;
  return std::max(0.0, overhead / gain);
}

Layout recommended(double cells, int ranks) {
  if (ranks < 2) return Layout::whole;
  return kSplitStep.seconds(cells / ranks) < kWholeStep.seconds(cells) ? Layout::split : Layout::whole;
}

std::string advice(double cells, int ranks, Layout running) {
  const Layout rule = recommended(cells, ranks);
  std::ostringstream out;
  out.precision(3);
  out << std::lround(cells) << " cells on " << ranks << " ranks, the gas " << name(running) << ": ";
  out << (rule == running ? "as the measured rule has it" : std::string("the measured rule would have it ") + name(rule));
  const double from = split_from_cells(ranks);
  out << " (";
  if (from >= 0) out << "split from " << std::lround(from) << " cells on " << ranks << " ranks; ";
  out << "gas step " << 1e3 * kWholeStep.seconds(cells) << " ms whole, " << 1e3 * kSplitStep.seconds(cells / ranks)
      << " ms split; bench/README.md)";
  if (rule != running)
    out << (rule == Layout::split ? ". Fix: decomposePar (numberOfSubdomains " + std::to_string(ranks) +
                                        "), mpirun -np " + std::to_string(ranks) + " tfdemFoam -parallel"
                                  : std::string(". Fix: mpirun -np ") + std::to_string(ranks) +
                                        " tfdemFoam without -parallel (after reconstructPar of a split checkpoint)");
  return out.str();
}

}  // namespace tfdem::gas_layout
