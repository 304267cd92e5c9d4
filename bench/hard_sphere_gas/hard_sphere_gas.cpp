// tfdem-hard-sphere-gas SNAPSHOT TIME [SEED]: the hard-sphere engine's event-driven flight
// (tfdem::hard_sphere::EventFlight) on an elastic, smooth gas in a periodic box, from a snapshot
// in the .sph format of Smallenburg's EDMD (2022): the count, the box's three sides, then one
// line "a x y z r" per sphere. Unit mass, Maxwellian velocities at kT = 1 with no total
// momentum (EDMD's units: diameter 1, mass 1, kT 1); flown for TIME in steps of one time unit.
// Prints the collisions, the flight's seconds (wall clock, without reading the file) and the
// microseconds per collision: bench.py runs it beside EDMD on the same snapshot.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "tfdem/hard_sphere/event_flight.h"

using tfdem::hard_sphere::CollisionLaw;
using tfdem::hard_sphere::EventFlight;
using tfdem::hard_sphere::Vec3;
using tfdem::hard_sphere::WallBox;

namespace {

struct Snapshot {
  double side[3] = {0, 0, 0};
  std::vector<Vec3> position;
  std::vector<double> radius;
};

Snapshot read_snapshot(const std::string &path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot be read");
  Snapshot s;
  std::size_t count = 0;
  in >> count >> s.side[0] >> s.side[1] >> s.side[2];
  std::string kind;
  for (std::size_t i = 0; i < count; ++i) {
    Vec3 x;
    double r;
    if (!(in >> kind >> x[0] >> x[1] >> x[2] >> r)) throw std::runtime_error(path + ": sphere " + std::to_string(i));
    for (int a = 0; a < 3; ++a) x[a] -= s.side[a] * std::floor(x[a] / s.side[a]);  // EDMD writes unwrapped
    s.position.push_back(x);
    s.radius.push_back(r);
  }
  return s;
}

}  // namespace

int main(int argc, char **argv) {
  if (argc < 3) {
    std::cerr << "usage: tfdem-hard-sphere-gas SNAPSHOT.sph TIME [SEED]\n";
    return 2;
  }
  try {
    const Snapshot snapshot = read_snapshot(argv[1]);
    const double time = std::atof(argv[2]);
    const unsigned seed = argc > 3 ? static_cast<unsigned>(std::atol(argv[3])) : 15485863u;
    WallBox box;
    for (int a = 0; a < 3; ++a) {
      box.upper[a] = snapshot.side[a];
      box.wall[a][0] = box.wall[a][1] = false;
      box.periodic[a] = true;
    }
    const CollisionLaw elastic{1, 0, 0};
    EventFlight gas(box, 1, {elastic}, {elastic}, 0, 1000000);
    if (argc > 4) gas.set_skin(std::atof(argv[4]));
    const std::size_t n = snapshot.position.size();
    std::mt19937 random(seed);
    std::normal_distribution<double> gauss(0, 1);
    std::vector<Vec3> v(n);
    Vec3 mean;
    for (Vec3 &x : v) mean += (x = {gauss(random), gauss(random), gauss(random)});
    mean = (1.0 / n) * mean;
    double energy = 0;
    for (Vec3 &x : v) {
      x -= mean;
      energy += dot(x, x);
    }
    const double scale = std::sqrt(3.0 * n / energy);  // kT = 1: sum v^2 = 3 N
    for (std::size_t i = 0; i < n; ++i) gas.add(snapshot.position[i], scale * v[i], {}, snapshot.radius[i], 1, 0);
    long collisions = 0, renewed = 0, predictions = 0;
    const auto start = std::chrono::steady_clock::now();
    for (double t = 0; t < time - 1e-12; t += 1) {
      const tfdem::hard_sphere::FlightCounts c = gas.fly(std::min(1.0, time - t));
      collisions += c.pair, renewed += c.lists_renewed, predictions += c.predictions;
    }
    std::printf("renewed %ld\npredictions %ld\n", renewed, predictions);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("spheres %zu\ncollisions %ld\nseconds %.6f\nmicroseconds per collision %.4f\n", n, collisions,
                seconds, 1e6 * seconds / collisions);
  } catch (const std::exception &e) {
    std::cerr << "tfdem-hard-sphere-gas: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
