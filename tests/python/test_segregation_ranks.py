"""studies/bidisperse_segregation/ranks.py's comparison of N ranks with one rank on hand-made
realizations, answers by hand:

- Delta p 100, 102, 104 Pa on one rank and 101, 105, 103 on four: means 102 and 103, each
  with the standard error 2 / sqrt(3) = 1.1547 (sample standard deviation 2 both), so the
  difference is +1 +- 1.6330 Pa, +0.612 standard errors;
- solids-fraction maps uniform at 0, 0.1, 0.2 on one rank and 0.05, 0.15, 0.25 on four: the
  floors are the mean of |0.1|, |0.2|, |0.1| = 0.1333 each, the cross L1 the mean of the nine
  |a - b| (0.05 five times, 0.15 three times, 0.25 once) = 0.95 / 9 = 0.10556;
- maps 0 on one rank and 1 on four: of the C(6, 3) = 20 relabellings only the true split and
  its mirror reach the observed statistic, so p = 2 / 20 = 0.1, the smallest 3 + 3 maps give;
- one realization on four ranks, 107 Pa: its error is the one-rank spread 2, so the difference
  is +5 +- sqrt(4/3 + 4) = 2.3094 Pa, +2.165 standard errors; its map uniform at 0.3 against
  0, 0.1, 0.2 gives the cross L1 (0.3 + 0.2 + 0.1) / 3 = 0.2, and neither a floor within four
  ranks nor a permutation test (one map);
- the table names every metric and the rank count, and says when one map stands alone.
"""
import math
import os
import sys

import numpy

from tfdem import STUDIES

sys.path.insert(0, os.path.join(STUDIES, "bidisperse_segregation"))
import ranks  # noqa: E402

failures = []


def check(name, condition, detail=""):
    print(("PASS " if condition else "FAIL ") + name + (f" {detail}" if detail else ""))
    if not condition:
        failures.append(name)


def main():
    one = {key: [100.0, 102.0, 104.0] for key in ranks.METRICS}
    many = {key: [101.0, 105.0, 103.0] for key in ranks.METRICS}
    c = ranks.compare(one, many)["dp_mean"]
    check("one rank: 102 +- 1.1547", abs(c["one_rank"]["mean"] - 102) < 1e-12
          and abs(c["one_rank"]["error"] - 2 / math.sqrt(3)) < 1e-12, str(c["one_rank"]))
    check("four ranks: 103 +- 1.1547", abs(c["many_ranks"]["mean"] - 103) < 1e-12
          and abs(c["many_ranks"]["error"] - 2 / math.sqrt(3)) < 1e-12, str(c["many_ranks"]))
    check("difference +1 +- 1.6330", abs(c["difference"]["mean"] - 1) < 1e-12
          and abs(c["difference"]["error"] - 1.6329932) < 1e-7, str(c["difference"]))
    check("+0.612 standard errors", abs(c["in_errors"] - 0.6123724) < 1e-7, f"{c['in_errors']:.7f}")

    def uniform(v):
        return numpy.full((3, 2), v)
    m = ranks.maps_comparison([uniform(v) for v in (0, 0.1, 0.2)], [uniform(v) for v in (0.05, 0.15, 0.25)])
    check("floor within one rank 0.1333", abs(m["floor_one_rank"] - 0.4 / 3) < 1e-12, str(m))
    check("floor within four ranks 0.1333", abs(m["floor_many_ranks"] - 0.4 / 3) < 1e-12, str(m))
    check("cross L1 0.10556", abs(m["cross"] - 0.95 / 9) < 1e-12, str(m))
    apart = ranks.maps_comparison([uniform(0)] * 3, [uniform(1)] * 3)
    check("maps apart: p = 2/20", abs(apart["p"] - 0.1) < 1e-12 and abs(apart["cross"] - 1) < 1e-12, str(apart))

    result = {"ranks": 4, "realizations": 3, "many_realizations": 3, "window": [0.3, 1.0],
              "metrics": ranks.compare(one, many), "maps": m}
    text = ranks.table(result)
    check("table: a row per metric, 4 ranks named",
          all(label in text for label, _, _ in ranks.METRICS.values()) and "| 4 ranks |" in text, text)

    single = ranks.compare(one, {key: [107.0] for key in ranks.METRICS})["dp_mean"]
    check("one realization on four ranks: +-2, the one-rank spread",
          single["many_ranks"]["n"] == 1 and abs(single["many_ranks"]["error"] - 2) < 1e-12, str(single["many_ranks"]))
    check("one realization: difference +5 +- 2.3094",
          abs(single["difference"]["mean"] - 5) < 1e-12
          and abs(single["difference"]["error"] - math.sqrt(16 / 3)) < 1e-12, str(single["difference"]))
    check("one realization: +2.165 standard errors", abs(single["in_errors"] - 5 / math.sqrt(16 / 3)) < 1e-12)
    lone = ranks.maps_comparison([uniform(v) for v in (0, 0.1, 0.2)], [uniform(0.3)])
    check("one map on four ranks: cross 0.2, no floor within, no test",
          abs(lone["cross"] - 0.2) < 1e-12 and lone["floor_many_ranks"] is None and lone["p"] is None, str(lone))
    text = ranks.table({"ranks": 4, "realizations": 3, "many_realizations": 1, "window": [0.3, 0.5],
                        "metrics": ranks.compare(one, {key: [107.0] for key in ranks.METRICS}), "maps": lone})
    check("table with one map on many ranks says so", "one map on many ranks" in text and "1 on 4" in text, text)
    check("runs: 3 realizations on 1 rank, 1 on 4",
          [r.name for r in ranks.runs(4, 3, 1)] == ["rank1_r1", "rank1_r2", "rank1_r3", "ranks4_r1"])
    print("all passed" if not failures else f"{len(failures)} failed: {failures}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
