// Free flight with hard-sphere collisions over one flow step (seed 001 sec. 3.3, Fig. 5): the
// particles move on straight lines between collisions, processed one by one in the order they
// occur (event-driven), each by tfdem::hard_sphere::collide (eqs. 11-21).
//
// The search is restricted as in eq. 44 by neighbour lists: each particle has an anchor (its
// position when its list was last made), and a pair is listed while its anchors lie within
// R_a + R_b + skin. Each particle's predicted events include leaving the sphere of radius
// skin / 2 about its anchor (the time solved exactly on its straight path), upon which its
// list alone is made again about its new anchor, in its partners' lists too. Two unlisted
// particles, each within skin / 2 of an anchor more than R_a + R_b + skin from the other's,
// cannot touch, whatever their speeds: the lists hold without any bound on the velocities or
// the flow step, and a bed's slow particles keep theirs for many steps while its fast ones
// renew theirs often. The anchors are binned in cells of the largest reach. The time to a
// collision is eq. 45, written
// without its cancellation, t = c / (-b + sqrt(b^2 - u^2 c)), b = r.u, c = r^2 - (R_a + R_b)^2:
// a pair moving apart (b >= 0) never collides; one that touches or overlaps (c <= 0, by
// round-off or from a soft-sphere packing) while approaching collides at once. Each particle
// holds one predicted event (eqs. 46-47) in a heap; an event stale after either partner
// collided (collision counters) is dropped when it comes up and its particle predicted anew.
// Walls are the planes of a box (infinite mass); a side without one is open; an axis may
// instead be periodic (a granular gas without walls).
//
// A packing made with soft spheres holds pairs that overlap by a few % of d and spheres sunk
// into walls. Hard spheres cannot push them apart, and a network of overlapping pairs
// collides at one instant without end. tolerate_overlaps() takes such a pair as touching at
// its present distance (or sphere at its present gap to the wall): that contact distance grows
// back to R_a + R_b as the pair parts (updated at the start of every flow step), and is
// forgotten once it has.
//
// Inelastic collapse (seed 001 sec. 2.1: collision rates diverge as relative velocities vanish
// in dense, dissipative beds) is kept off by the TC model of Luding and McNamara (1998): a
// collision within `elastic_within` seconds of either particle's previous one is elastic and
// smooth, or (set_tc_keeps_friction) elastic in the normal direction only: friction does not
// drive the collapse (a tangential impulse leaves the normal relative velocity as it is), and
// it is most of the dissipation of glass beads at e_n 0.97. A flow step with more than
// `max_collisions_per_particle` collisions per particle stops with a message (a bed the
// event-driven model cannot carry).
#ifndef TFDEM_HARD_SPHERE_EVENT_FLIGHT_H
#define TFDEM_HARD_SPHERE_EVENT_FLIGHT_H

#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "tfdem/hard_sphere/collision.h"
#include "tfdem/hard_sphere/vec3.h"

namespace tfdem::hard_sphere {

// The box's planes; wall[a][side] (side 0 lower, 1 upper): a wall there, else open, unless
// the axis is periodic (then it has no walls, and at least 3 neighbour cells across).
struct WallBox {
  double lower[3] = {0, 0, 0}, upper[3] = {1, 1, 1};
  bool wall[3][2] = {{true, true}, {true, true}, {true, true}};
  bool periodic[3] = {false, false, false};
};

// Collisions of one flow step.
struct FlightCounts {
  long pair = 0, wall = 0;      // collisions processed
  long elastic = 0;              // of them, made elastic by the TC model
  long predictions = 0;          // particles whose next event was predicted
  long list_builds = 0;          // neighbour lists of all particles built
  long lists_renewed = 0;        // particles' own lists made again (left their anchor's sphere)
};

class EventFlight {
 public:
  // Per-particle state, structure of arrays (the engine owns and edits it between steps)
  std::vector<Vec3> position, velocity, spin;
  std::vector<double> radius, mass;
  std::vector<int> type;           // 0 .. type_count - 1
  std::vector<Vec3> impulse;       // sum of the impulses of the last step, per particle (N s)
  std::vector<double> last_collision;  // clock time of each particle's last collision (s)

  // pair_laws[a * type_count + b] (symmetric), wall_laws[a]
  EventFlight(const WallBox &box, int type_count, std::vector<CollisionLaw> pair_laws,
              std::vector<CollisionLaw> wall_laws, double elastic_within, long max_collisions_per_particle);
  // No particles in the unit box, elastic and smooth (to be assigned a flight)
  EventFlight() : EventFlight(WallBox{}, 1, {CollisionLaw{}}, {CollisionLaw{}}, 0, 1) {}

  // Move every particle over `dt` seconds from the clock on, colliding as they meet; the
  // clock advances by dt. Throws std::runtime_error for more collisions than the bound.
  FlightCounts fly(double dt);

  // The TC model's collisions: elastic and smooth (false, Luding & McNamara's), or elastic in
  // the normal direction only, with the pair's friction and tangential restitution (true)
  void set_tc_keeps_friction(bool keep) { tc_keeps_friction_ = keep; }
  // The skin in largest diameters (default 0.2; the lists are built again at the next step)
  void set_skin(double diameters) { skin_diameters_ = diameters; lists_.built = false; }
  double clock() const { return clock_; }
  void set_clock(double t) { clock_ = t; }
  std::size_t size() const { return position.size(); }
  // Add a particle (type 0-based); remove particles by index (order of the rest kept)
  void add(const Vec3 &x, const Vec3 &v, const Vec3 &w, double r, double m, int type);
  void remove(std::vector<std::size_t> indices);
  const WallBox &box() const { return box_; }
  // Take the pairs overlapping now, and the spheres sunk into a wall, as touching where they
  // are (see above): how many, and the deepest overlap as a fraction of the smaller diameter
  struct Overlaps {
    std::size_t pairs = 0, walls = 0;
    double deepest = 0;
  };
  Overlaps tolerate_overlaps();
  // The tolerated contacts, to save and restore with the particles (a restart)
  const std::unordered_map<std::uint64_t, double> &tolerated() const { return tolerated_; }
  const std::vector<double> &wall_reach() const { return reach_; }
  void restore_tolerated(std::unordered_map<std::uint64_t, double> pairs, std::vector<double> reach);
  // The neighbour lists as they stand, and the same restored (a restart): a run resumed with
  // them takes the straight run's steps bit for bit (the lists decide which events are
  // predicted and in what order ties fall)
  struct NeighbourLists {
    bool built = false;
    // particle i's partners are partners[i * capacity ...] (degree[i] of them), with each
    // listed pair's contact distance (R_a + R_b, or less) beside them
    std::vector<Vec3> anchor;
    std::vector<int> partners, degree;
    std::vector<double> contact;
    int capacity = 0;
    double skin = 0;
    // the anchors' cells: cells per axis of width, a doubly linked list of particles per cell
    int cells[3] = {1, 1, 1};
    double width[3] = {1, 1, 1};
    std::vector<int> head, next, previous, cell;
  };
  const NeighbourLists &lists() const { return lists_; }
  void restore_lists(NeighbourLists lists);
  // Open a face of the box (no wall there: an outlet)
  void open(int axis, int side) { box_.wall[axis][side] = false; }

 private:
  struct Event {
    double time;
    int particle, partner;  // partner < 0: wall -1 - (2 axis + side)
    long count, partner_count;
    bool operator>(const Event &o) const { return time > o.time; }
  };

  // Every particle's anchor at its position at `now`, and the lists of all pairs
  void build_lists(double now);
  // Particle i's anchor moved to its position at `now`, its list made again (and it in its
  // partners'); false when a partner's list is full (then build_lists)
  bool renew_list(int i, double now);
  // The partners of particle i about the anchors, appended to `out` with their contact distance
  void gather(int i, std::vector<int> &out, std::vector<double> &contact) const;
  // The contact distance of a listed pair: R_a + R_b, or a tolerated overlap's
  double contact_distance(int i, int j) const;
  // The tolerated pairs' contact distances and the spheres' wall reach grown towards the
  // present distances (those that have parted forgotten)
  void relax_tolerated();
  void set_listed_contact(int i, int j, double distance);
  int cell_of(const Vec3 &x) const;
  void link(int i, int cell);
  void unlink(int i);
  // r with the periodic axes' nearest image
  Vec3 nearest(Vec3 r) const {
    if (!periodic_) return r;
    return wrapped(r);
  }
  Vec3 wrapped(Vec3 r) const;
  void predict(int i, double now, double end);
  // predict() for every particle, each listed pair's time computed once for both partners
  // (the same earliest events, at half the pair tests: after each drag kick all of them)
  void predict_all(double now, double end);
  // particle i's earliest event among the walls and its anchor's sphere, if before `best`
  void predict_boundaries(int i, const Vec3 &xi, const Vec3 &vi, double now, double &best, int &partner) const;
  // particle i's event at `time` with `partner`, stamped with both collision counts
  Event event_of(int i, double time, int partner) const {
    return {time, i, partner, count_[i], partner >= 0 ? count_[partner] : 0};
  }
  void push_event(int i, double time, int partner);
  // The message of a flow step that ran out of collisions, with its likely cause and fix
  std::string collapse(int n, double dt, double when, double last_half) const;
  void advance_to(int i, double t);
  const CollisionLaw &law(int a, int b) const { return pair_laws_[type[a] * type_count_ + type[b]]; }

  WallBox box_;
  int type_count_;
  std::vector<CollisionLaw> pair_laws_, wall_laws_;
  double elastic_within_;
  long max_collisions_per_particle_;
  double clock_ = 0;
  // The skin, in largest diameters: a pair is listed while its anchors are within R_a + R_b +
  // skin (a thicker skin lists more partners to scan at each prediction, a thinner one makes
  // particles leave their anchor's sphere, and renew their lists, more often)
  double skin_diameters_ = 0.2;
  bool tc_keeps_friction_ = false;
  // The law of a collision the TC model makes elastic
  CollisionLaw tc_law(const CollisionLaw &law) const {
    return tc_keeps_friction_ ? CollisionLaw{1, law.friction, law.tangential_restitution} : CollisionLaw{1, 0, 0};
  }
  // within a step: each particle's position at its time t and its velocity, packed in one
  // cache line (the predictions read a partner's at once), and its collision counter
  struct alignas(64) Motion {
    Vec3 x;
    double t;
    Vec3 v;
  };
  std::vector<Motion> motion_;
  std::vector<long> count_;
  // motion_ from position and velocity at time 0, and back
  void pack();
  void unpack();
  NeighbourLists lists_;
  // tolerated overlaps: pair (i << 32 | j, i < j) -> its contact distance; each sphere's reach
  // towards each of the 6 walls (its radius, or less)
  std::unordered_map<std::uint64_t, double> tolerated_;
  std::vector<double> reach_;
  bool periodic_ = false;
  std::vector<Event> heap_;
  std::vector<Vec3> now_position_;  // predict_all's positions at its instant
  std::vector<double> best_time_;
  std::vector<int> best_partner_;
  FlightCounts counts_;
};

}  // namespace tfdem::hard_sphere

#endif
