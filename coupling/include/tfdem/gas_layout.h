// Which way the gas goes on several ranks: whole on every rank (mpirun without -parallel) or
// split between them (decomposePar, -parallel), by the gas step's cost measured on this
// machine kind (bench/README.md, "Cost against bed size": fits to the bubbling bed at
// 675-10,800 cells on 1 and 2 ranks). With the gas whole every rank pays the serial step; split,
// each pays the step of its part plus the reductions' latency, which the fixed cost carries.
// The particles are LIGGGHTS' to split either way, and the DEM is 85-97 % of a step in every
// bed measured, so the layout moves the gas's part alone.
#ifndef TFDEM_GAS_LAYOUT_H
#define TFDEM_GAS_LAYOUT_H

#include <string>

namespace tfdem::gas_layout {

// A gas step's wall time: fixed + per_cell x cells (of the whole mesh, or of one rank's part).
struct StepCost {
  double fixed_seconds;
  double per_cell_seconds;
  double seconds(double cells) const { return fixed_seconds + per_cell_seconds * cells; }
};
constexpr StepCost kWholeStep{0.63e-3, 3.8e-6};  // serial step, 1 rank (= each rank, gas whole)
constexpr StepCost kSplitStep{2.2e-3, 4.4e-6};   // a split step, 2 ranks, per cell of a part

enum class Layout { whole, split };
const char *name(Layout layout);

// The fewest cells from which the split step over `ranks` is the shorter:
// (split.fixed - whole.fixed) / (whole.per_cell - split.per_cell / ranks); 0 when split is
// always shorter, a negative number when it never is (1 rank; or per-cell costs that never
// catch up).
double split_from_cells(int ranks);

// The layout with the shorter gas step for `cells` cells on `ranks` ranks (whole for 1 rank).
Layout recommended(double cells, int ranks);

// One sentence on the layout a run uses against the rule's, with the fix when they differ,
// e.g. "675 cells on 2 ranks, the gas whole: as the measured rule has it (split from 981
// cells on 2 ranks; gas step 3.2 ms whole, 3.7 ms split)".
std::string advice(double cells, int ranks, Layout running);

}  // namespace tfdem::gas_layout

#endif
