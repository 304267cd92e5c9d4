#include "tfdem/packing_check.h"

#include <algorithm>
#include <cmath>

#include "tfdem/analysis.h"

namespace tfdem {

PackingCheck check_packing(const ParticleView &p) {
  PackingCheck check;
  std::vector<std::size_t> finite;
  for (std::size_t i = 0; i < p.count; ++i) {
    bool ok = std::isfinite(p.diameter[i]);
    for (int a = 0; a < 3; ++a)
      ok = ok && std::isfinite(p.position[3 * i + a]) && (!p.velocity || std::isfinite(p.velocity[3 * i + a]));
    (ok ? finite : check.not_finite).push_back(i);
  }
  std::vector<double> x(3 * finite.size()), d(finite.size());
  for (std::size_t k = 0; k < finite.size(); ++k) {
    for (int a = 0; a < 3; ++a) x[3 * k + a] = p.position[3 * finite[k] + a];
    d[k] = p.diameter[finite[k]];
  }
  ParticleView view;
  view.count = finite.size();
  view.position = x.data();
  view.diameter = d.data();
  for (const auto &[i, j] : analysis::contact_pairs(view)) {
    const double *xi = &x[3 * i], *xj = &x[3 * j];
    const double distance = std::sqrt((xi[0] - xj[0]) * (xi[0] - xj[0]) + (xi[1] - xj[1]) * (xi[1] - xj[1]) +
                                      (xi[2] - xj[2]) * (xi[2] - xj[2]));
    const std::size_t a = std::min(finite[i], finite[j]), b = std::max(finite[i], finite[j]);
    if (distance < kCoincident * std::min(d[i], d[j])) check.coincident.emplace_back(a, b);
    check.overlaps.push_back({a, b, 0.5 * (d[i] + d[j]) - distance});
  }
  return check;
}

}  // namespace tfdem
