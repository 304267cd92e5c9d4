"""The DPMFoam comparison's contact mapping (bench/peer_dpmfoam/peer.py): LIGGGHTS' Hertz
restitution e = exp(beta pi / sqrt(1 - beta^2)), beta = -alpha / sqrt(5), against one head-on
collision integrated (RK4) with DPMFoam's law m x'' = -k x^1.5 - alpha sqrt(m k) x^0.25 x',
for DPMFoam Goldschmidt's alpha 0.02 and 0.01 and a stiffer damping 0.3, at two impact speeds
(e of this law does not depend on the speed). By hand: alpha 0.02 gives beta = -0.0089443,
ln e = -0.028101, e = 0.97229.
"""
import importlib.util
import os

from tfdem import SOURCE_DIR
from tfdem_testlib import Checks

PEER = os.path.join(SOURCE_DIR, "bench", "peer_dpmfoam", "peer.py")


def main():
    spec = importlib.util.spec_from_file_location("peer", PEER)
    peer = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(peer)
    checks = Checks()
    checks.within("e for alpha 0.02 by hand", peer.restitution(0.02), 0.97229, 5e-6)
    for alpha in (0.02, 0.01, 0.3):
        for speed in (1.0, 0.1):
            checks.within(f"alpha {alpha}, impact speed {speed}: closed form against the integrated collision",
                          peer.restitution(alpha), peer.integrated_restitution(alpha, speed), 1e-5)
    checks.finish()


if __name__ == "__main__":
    main()
