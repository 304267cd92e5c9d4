"""Reference physics the tutorials and tests compare with: the paper's drag law, Ergun's fixed
bed, minimum fluidization and a lone settling sphere. Pure formulas in SI units; the numbers
(diameters, densities, gas, gravity, cells) come from a case through tfdem.case.

Seeds: 000 = hybrid TF-DEM, J. Fluids Eng. 129 (2007); 001 = Deen et al., Chem. Eng. Sci. 62
(2007) (../shared/seeds/). Every formula names its equation there, or says that it is not one.
"""
import math


def archimedes(d, rho_p, rho_g, mu, g):
    """Archimedes number Ar = rho_g (rho_p - rho_g) g d^3 / mu^2 (the definition used with
    Wen and Yu's correlation; not an equation of the seeds)."""
    return rho_g * (rho_p - rho_g) * g * d ** 3 / mu ** 2


def drag_coefficient(re):
    """C_D of a sphere at particle Reynolds number re > 0: seed 000 eq. 31 (24 (1 + 0.15
    Re^0.687) / Re below Re = 1000, 0.43 above)."""
    return 24.0 * (1.0 + 0.15 * re ** 0.687) / re if re < 1000 else 0.43


def beta_over_solid_fraction(eps_g, slip, d, rho_g, mu):
    """beta / eps_s (kg/m^3/s) of the drag law `ergun_wen_yu` at gas fraction eps_g and slip
    speed |u_g - v_p|: seed 000 eq. 30 (Ergun below eps_g = 0.8, Wen and Yu with eps_g^-2.7
    above) with C_D of eq. 31 and Re_p = eps_g rho_g |slip| d / mu."""
    eps_s = 1.0 - eps_g
    if eps_g < 0.8:
        return 150.0 * eps_s * mu / (eps_g * d ** 2) + 1.75 * rho_g * abs(slip) / d
    re = eps_g * rho_g * abs(slip) * d / mu
    if re == 0.0:
        return 18.0 * mu / d ** 2 * eps_g ** -2.7  # the Stokes limit of 0.75 C_D Re mu / d^2
    return 0.75 * drag_coefficient(re) * eps_g * rho_g * abs(slip) / d * eps_g ** -2.7


def ergun_gradient(u, eps, d, rho_g, mu):
    """Ergun (1952): pressure drop per bed length (Pa/m) of a fixed bed of gas fraction eps at
    superficial velocity u, 150 eps_s^2 mu u / (eps^3 d^2) + 1.75 eps_s rho_g u^2 / (eps^3 d).
    It is seed 000 eq. 30's eps_g < 0.8 branch in a fixed bed, where the gas momentum balance
    (seed 000 eq. 28 and 32-33 summed over the bed) is eps dp/dy = beta u_g with the
    interstitial u_g = u / eps. (Seed 001 eq. 3 prints the inertial term with Re = eps_g rho
    |u_g| d / mu, an extra eps_g that coupling/src/drag.cpp reads as a misprint.)"""
    eps_s = 1.0 - eps
    return (150 * eps_s ** 2 * mu * u / (eps ** 3 * d ** 2)
            + 1.75 * eps_s * rho_g * u * u / (eps ** 3 * d))


def wen_yu_minimum_fluidization(d, rho_p, rho_g, mu, g):
    """Wen and Yu (1966) U_mf (m/s): Re_mf = sqrt(33.7^2 + 0.0408 Ar) - 33.7. Not an equation
    of the seeds (seed 000 ref. 23, seed 001's references; seed 000 Table 1 lists U_mf =
    1.28 m/s for its 2.5 mm beads)."""
    return (math.sqrt(33.7 ** 2 + 0.0408 * archimedes(d, rho_p, rho_g, mu, g)) - 33.7) * mu / (rho_g * d)


def ergun_minimum_fluidization(eps, d, rho_p, rho_g, mu, g):
    """U_mf (m/s) where ergun_gradient at gas fraction eps carries the net bed weight
    eps_s (rho_p - rho_g) g: 1.75/eps^3 Re^2 + 150 (1 - eps)/eps^3 Re = Ar (Re = rho_g U d /
    mu), the same balance as ergun_gradient (seed 000 eq. 30, eps_g < 0.8)."""
    a, b = 1.75 / eps ** 3, 150 * (1 - eps) / eps ** 3
    re = (-b + math.sqrt(b * b + 4 * a * archimedes(d, rho_p, rho_g, mu, g))) / (2 * a)
    return re * mu / (rho_g * d)


def sphere_volume_below(d, t):
    """Volume of a sphere of diameter d below a plane at signed distance t from its centre
    (a cap of height h = r + t: pi h^2 (3r - h)/3)."""
    r = 0.5 * d
    h = min(max(r + t, 0.0), 2 * r)
    return math.pi * h * h * (3 * r - h) / 3


def slab_solid_fraction(particles, y0, y1, area):
    """Solid fraction of the slab y0 < y < y1 of cross-section `area`: the exact volume of the
    spheres (dict of lists diameter, y) inside it, over the slab's volume."""
    solid = math.fsum(sphere_volume_below(d, y1 - y) - sphere_volume_below(d, y0 - y)
                      for d, y in zip(particles["diameter"], particles["y"]))
    return solid / (area * (y1 - y0))


def sphere_volume(d):
    return math.pi * d ** 3 / 6


class SettlingSphere:
    """A lone sphere settling from rest in still gas, in a cell of volume cell_volume:

        m dv/dt = -(m - rho_g V) g + V beta/eps_s (u_g - v),  u_g = 0

    seed 000 eq. 28-29 (the pressure-gradient force of the hydrostatic gas is the buoyancy
    rho_g V g), beta of eq. 30-31 at the cell's gas fraction eps_g = 1 - V / V_cell. v is the
    vertical velocity, up positive; integrated with RK4."""

    def __init__(self, d, rho_p, rho_g, mu, g, cell_volume):
        self.d, self.rho_p, self.rho_g, self.mu, self.g = d, rho_p, rho_g, mu, g
        self.eps = 1.0 - sphere_volume(d) / cell_volume

    @classmethod
    def from_case(cls, case):
        """The sphere of a tfdem.case.Case: d and rho_p of coupling.yaml, rho_g and mu of
        constant/transportProperties, |g| of constant/g, the cell of system/blockMeshDict; its
        drag law must be coupling.yaml's ergun_wen_yu."""
        law = case.coupling_value("coupling.drag_law")
        if law != "ergun_wen_yu":
            raise ValueError(f"{case.file('coupling.yaml')}: drag_law {law}: the settling ODE"
                             " follows ergun_wen_yu (seed 000 eq. 30-31) only")
        d, rho_p = case.particle_properties()
        rho_g, mu = case.gas()
        sx, sy, sz = case.grid().spacing
        return cls(d, rho_p, rho_g, mu, case.gravity_magnitude(), sx * sy * sz)

    def drag_per_volume(self, slip):
        """beta / eps_s (kg/m^3/s) at slip speed |u_g - v|."""
        return beta_over_solid_fraction(self.eps, slip, self.d, self.rho_g, self.mu)

    def acceleration(self, v):
        """dv/dt (m/s^2) at vertical velocity v (m/s, up positive)."""
        return -(1.0 - self.rho_g / self.rho_p) * self.g + self.drag_per_volume(-v) * (-v) / self.rho_p

    def velocity(self, times, dt=1e-6):
        """v(t) (m/s) at the given increasing times (s), from rest at t = 0."""
        out, v, t = [], 0.0, 0.0
        for target in times:
            while t < target - 1e-12:
                h = min(dt, target - t)
                k1 = self.acceleration(v)
                k2 = self.acceleration(v + 0.5 * h * k1)
                k3 = self.acceleration(v + 0.5 * h * k2)
                k4 = self.acceleration(v + h * k3)
                v += h * (k1 + 2 * k2 + 2 * k3 + k4) / 6
                t += h
            out.append(v)
        return out

    def terminal_velocity(self):
        """Settling speed (m/s, positive) where weight less buoyancy equals drag, by bisection."""
        lo, hi = 0.0, 100.0
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if self.acceleration(-mid) < 0 else (lo, mid)
        return 0.5 * (lo + hi)


class PlanePoiseuille:
    """Laminar flow between two plates h apart at mean velocity U (any textbook): parabolic
    u(y) = 6 U (y - y0)(y1 - y)/h^2, centreline 1.5 U, pressure gradient 12 mu U / h^2. From a
    channel case's own files: h from its mesh, U from its inlet, mu from transportProperties."""

    def __init__(self, case):
        lo, hi = case.mesh_bounds()
        self.y0, self.y1 = lo[1], hi[1]
        self.h = hi[1] - lo[1]
        self.u_mean = case.patch_value("U", "inlet")[0]
        _, self.mu = case.gas()

    def velocity(self, y):
        return 6 * self.u_mean * (y - self.y0) * (self.y1 - y) / self.h ** 2

    def centreline_velocity(self):
        return 1.5 * self.u_mean

    def pressure_drop(self, length):
        return 12 * self.mu * self.u_mean * length / self.h ** 2


def jenkins_zhang_effective_restitution(e, mu):
    """The effective normal restitution of rough, frictional spheres for a kinetic theory of
    smooth ones, e - 3/2 mu exp(-3 mu) (Jenkins & Zhang 2002, Phys. Fluids 14; Chialvo &
    Sundaresan 2013 use it the same way): the dissipation sliding friction adds. For mu up to
    ~0.5. Not an equation of the seeds."""
    return e - 1.5 * mu * math.exp(-3 * mu)
