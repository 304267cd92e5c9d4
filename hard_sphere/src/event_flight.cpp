#include "tfdem/hard_sphere/event_flight.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace tfdem::hard_sphere {
namespace {

// The skin, in largest diameters: a pair is listed while its anchors are within R_a + R_b +
// skin (a thicker skin lists more partners to scan at each prediction, a thinner one makes
// particles leave their anchor's sphere, and renew their lists, more often)
constexpr double kSkinDiameters = 0.2;
// A particle list's room beyond the most partners found at a full build
constexpr int kSpareFraction = 2, kLeastSpare = 8;
// The event of leaving the anchor's sphere (walls are -1 ... -6)
constexpr int kLeavesAnchor = -7;

std::uint64_t pair_key(int i, int j) {
  return (static_cast<std::uint64_t>(std::min(i, j)) << 32) | static_cast<std::uint32_t>(std::max(i, j));
}

template <typename T>
void keep(std::vector<T> &values, const std::vector<char> &drop) {
  std::size_t out = 0;
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!drop[i]) values[out++] = values[i];
  values.resize(out);
}

}  // namespace

EventFlight::EventFlight(const WallBox &box, int type_count, std::vector<CollisionLaw> pair_laws,
                         std::vector<CollisionLaw> wall_laws, double elastic_within, long max_collisions_per_particle)
    : box_(box),
      type_count_(type_count),
      pair_laws_(std::move(pair_laws)),
      wall_laws_(std::move(wall_laws)),
      elastic_within_(elastic_within),
      max_collisions_per_particle_(max_collisions_per_particle),
      periodic_(box.periodic[0] || box.periodic[1] || box.periodic[2]) {
  if (type_count_ < 1 || pair_laws_.size() != static_cast<std::size_t>(type_count_ * type_count_) ||
      wall_laws_.size() != static_cast<std::size_t>(type_count_))
    throw std::invalid_argument("EventFlight: collision laws for " + std::to_string(type_count_) +
                                " particle types need that many squared pairs and one wall law each");
}

void EventFlight::add(const Vec3 &x, const Vec3 &v, const Vec3 &w, double r, double m, int t) {
  if (t < 0 || t >= type_count_) throw std::invalid_argument("EventFlight::add: type " + std::to_string(t));
  position.push_back(x);
  velocity.push_back(v);
  spin.push_back(w);
  radius.push_back(r);
  mass.push_back(m);
  type.push_back(t);
  impulse.push_back({});
  last_collision.push_back(-std::numeric_limits<double>::infinity());
  reach_.insert(reach_.end(), 6, r);
  lists_built_ = false;
}

void EventFlight::remove(std::vector<std::size_t> indices) {
  std::vector<char> drop(size(), 0);
  for (const std::size_t i : indices) drop.at(i) = 1;
  keep(position, drop);
  keep(velocity, drop);
  keep(spin, drop);
  keep(radius, drop);
  keep(mass, drop);
  keep(type, drop);
  keep(impulse, drop);
  keep(last_collision, drop);
  std::vector<char> drop_reach(reach_.size());
  for (std::size_t i = 0; i < drop.size(); ++i)
    for (int p = 0; p < 6; ++p) drop_reach[6 * i + p] = drop[i];
  keep(reach_, drop_reach);
  if (!tolerated_.empty()) {  // renumber the tolerated pairs
    std::vector<int> renumbered(drop.size(), -1);
    int next = 0;
    for (std::size_t i = 0; i < drop.size(); ++i)
      if (!drop[i]) renumbered[i] = next++;
    std::unordered_map<std::uint64_t, double> kept;
    for (const auto &[key, distance] : tolerated_) {
      const int i = renumbered[key >> 32], j = renumbered[key & 0xffffffffu];
      if (i >= 0 && j >= 0) kept[pair_key(i, j)] = distance;
    }
    tolerated_.swap(kept);
  }
  lists_built_ = false;
}

void EventFlight::restore_tolerated(std::unordered_map<std::uint64_t, double> pairs, std::vector<double> reach) {
  if (reach.size() != 6 * size())
    throw std::invalid_argument("EventFlight::restore_tolerated: " + std::to_string(reach.size()) +
                                " wall reaches for " + std::to_string(size()) + " particles");
  tolerated_ = std::move(pairs);
  reach_ = std::move(reach);
  lists_built_ = false;
}

EventFlight::Overlaps EventFlight::tolerate_overlaps() {
  Overlaps o;
  const int n = static_cast<int>(size());
  pack();
  build_lists(0);
  for (int i = 0; i < n; ++i) {
    for (int k = i * capacity_; k < i * capacity_ + degree_[i]; ++k) {
      const int j = partners_[k];
      if (j <= i) continue;
      const double sigma = radius[i] + radius[j], distance = norm(nearest(position[i] - position[j]));
      if (distance >= sigma) continue;
      tolerated_[pair_key(i, j)] = distance;
      ++o.pairs;
      o.deepest = std::max(o.deepest, (sigma - distance) / (2 * std::min(radius[i], radius[j])));
    }
    for (int a = 0; a < 3; ++a)
      for (int side = 0; side < 2; ++side) {
        if (!box_.wall[a][side] || box_.periodic[a]) continue;
        const double gap = side == 0 ? position[i][a] - box_.lower[a] : box_.upper[a] - position[i][a];
        if (gap >= radius[i]) continue;
        reach_[6 * i + 2 * a + side] = std::max(gap, 0.0);
        ++o.walls;
        o.deepest = std::max(o.deepest, (radius[i] - gap) / (2 * radius[i]));
      }
  }
  lists_built_ = false;  // built again with the contact distances
  return o;
}

void EventFlight::pack() {
  motion_.resize(size());
  for (std::size_t i = 0; i < size(); ++i) motion_[i] = {position[i], 0, velocity[i]};
}

void EventFlight::unpack() {
  for (std::size_t i = 0; i < size(); ++i) position[i] = motion_[i].x, velocity[i] = motion_[i].v;
}

void EventFlight::advance_to(int i, double t) {
  Motion &m = motion_[i];
  m.x += (t - m.t) * m.v;
  m.t = t;
  if (!periodic_) return;
  for (int a = 0; a < 3; ++a)
    if (box_.periodic[a]) {
      const double span = box_.upper[a] - box_.lower[a];
      m.x[a] -= span * std::floor((m.x[a] - box_.lower[a]) / span);
    }
}

Vec3 EventFlight::wrapped(Vec3 r) const {
  for (int a = 0; a < 3; ++a)
    if (box_.periodic[a]) {
      const double span = box_.upper[a] - box_.lower[a];
      if (r[a] > 0.5 * span) r[a] -= span;
      else if (r[a] < -0.5 * span) r[a] += span;
    }
  return r;
}

int EventFlight::cell_of(const Vec3 &x) const {
  int c[3];
  for (int a = 0; a < 3; ++a)
    c[a] = std::clamp(static_cast<int>(std::floor((x[a] - box_.lower[a]) / width_[a])), 0, cells_[a] - 1);
  return c[0] + cells_[0] * (c[1] + cells_[1] * c[2]);
}

void EventFlight::link(int i, int cell) {
  cell_[i] = cell;
  previous_[i] = -1;
  next_[i] = head_[cell];
  if (next_[i] >= 0) previous_[next_[i]] = i;
  head_[cell] = i;
}

void EventFlight::unlink(int i) {
  if (previous_[i] >= 0) next_[previous_[i]] = next_[i];
  else head_[cell_[i]] = next_[i];
  if (next_[i] >= 0) previous_[next_[i]] = previous_[i];
}

double EventFlight::contact_distance(int i, int j) const {
  if (!tolerated_.empty()) {
    const auto found = tolerated_.find(pair_key(i, j));
    if (found != tolerated_.end()) return found->second;
  }
  return radius[i] + radius[j];
}

void EventFlight::gather(int i, std::vector<int> &out, std::vector<double> &contact) const {
  const int c = cell_[i];
  const int ci[3] = {c % cells_[0], (c / cells_[0]) % cells_[1], c / (cells_[0] * cells_[1])};
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        int cc[3] = {ci[0] + dx, ci[1] + dy, ci[2] + dz};
        bool inside = true;
        for (int a = 0; a < 3; ++a) {
          if (box_.periodic[a]) cc[a] = (cc[a] + cells_[a]) % cells_[a];
          inside = inside && cc[a] >= 0 && cc[a] < cells_[a];
        }
        if (!inside) continue;
        for (int j = head_[cc[0] + cells_[0] * (cc[1] + cells_[1] * cc[2])]; j >= 0; j = next_[j]) {
          if (j == i) continue;
          const Vec3 r = nearest(anchor_[i] - anchor_[j]);
          const double within = radius[i] + radius[j] + skin_;
          if (dot(r, r) >= within * within) continue;
          out.push_back(j);
          contact.push_back(contact_distance(i, j));
        }
      }
}

void EventFlight::build_lists(double now) {
  ++counts_.list_builds;
  const int n = static_cast<int>(size());
  double largest = 0;
  anchor_.resize(n);
  for (int i = 0; i < n; ++i) {
    advance_to(i, now);
    anchor_[i] = motion_[i].x;
    largest = std::max(largest, radius[i]);
  }
  lists_built_ = true;
  if (n == 0) {  // a bed emptied through its outlets: no lists, no cells
    degree_.clear();
    return;
  }
  skin_ = kSkinDiameters * 2 * largest;
  // cells at least as wide as the farthest reach of a listed pair's anchors
  const double reach = 2 * largest + skin_;
  for (int a = 0; a < 3; ++a)
    if (box_.periodic[a] && box_.upper[a] - box_.lower[a] < 3 * reach)
      throw std::invalid_argument("EventFlight: a periodic axis " + std::to_string(box_.upper[a] - box_.lower[a]) +
                                  " m long holds fewer than 3 neighbour cells of " + std::to_string(reach) + " m");
  // no more cells than a few per sphere: a few small spheres in a big box (a settling
  // sphere) would otherwise clear millions of empty cells at every build
  const long most_cells = std::max(64L, 8L * n);
  long total = 0;
  for (double cell_reach = reach; total == 0 || total > most_cells; cell_reach *= 1.25) {
    total = 1;
    for (int a = 0; a < 3; ++a) {
      const double span = box_.upper[a] - box_.lower[a];
      cells_[a] = std::max(box_.periodic[a] ? 3 : 1, std::min(4096, static_cast<int>(span / cell_reach)));
      width_[a] = span / cells_[a];
      total *= cells_[a];
    }
  }
  degree_.clear();  // the old lists go: no contact distance to keep in them
  head_.assign(total, -1);
  next_.assign(n, -1);
  previous_.assign(n, -1);
  cell_.assign(n, 0);
  for (int i = n - 1; i >= 0; --i) link(i, cell_of(anchor_[i]));  // each cell in index order
  relax_tolerated();
  std::vector<int> found;
  std::vector<double> contact;
  std::vector<int> first(n + 1, 0);
  for (int i = 0; i < n; ++i) {
    gather(i, found, contact);
    first[i + 1] = static_cast<int>(found.size());
  }
  int most = 0;
  for (int i = 0; i < n; ++i) most = std::max(most, first[i + 1] - first[i]);
  capacity_ = most + std::max(kLeastSpare, most / kSpareFraction);
  partners_.assign(static_cast<std::size_t>(n) * capacity_, -1);
  contact_.assign(static_cast<std::size_t>(n) * capacity_, 0);
  degree_.assign(n, 0);
  for (int i = 0; i < n; ++i) {
    degree_[i] = first[i + 1] - first[i];
    std::copy(found.begin() + first[i], found.begin() + first[i + 1], partners_.begin() + i * capacity_);
    std::copy(contact.begin() + first[i], contact.begin() + first[i + 1], contact_.begin() + i * capacity_);
  }
}

bool EventFlight::renew_list(int i, double now) {
  ++counts_.lists_renewed;
  advance_to(i, now);
  anchor_[i] = motion_[i].x;
  unlink(i);
  link(i, cell_of(anchor_[i]));
  for (int k = i * capacity_; k < i * capacity_ + degree_[i]; ++k) {  // out of the old partners' lists
    const int j = partners_[k], begin = j * capacity_, end = begin + degree_[j];
    for (int m = begin; m < end; ++m)
      if (partners_[m] == i) {
        partners_[m] = partners_[end - 1];
        contact_[m] = contact_[end - 1];
        --degree_[j];
        break;
      }
  }
  static thread_local std::vector<int> found;
  static thread_local std::vector<double> contact;
  found.clear();
  contact.clear();
  gather(i, found, contact);
  if (static_cast<int>(found.size()) > capacity_) return false;
  for (std::size_t k = 0; k < found.size(); ++k) {
    const int j = found[k];
    if (degree_[j] == capacity_) return false;
    partners_[j * capacity_ + degree_[j]] = i;
    contact_[j * capacity_ + degree_[j]] = contact[k];
    ++degree_[j];
    partners_[i * capacity_ + k] = j;
    contact_[i * capacity_ + k] = contact[k];
  }
  degree_[i] = static_cast<int>(found.size());
  return true;
}

void EventFlight::set_listed_contact(int i, int j, double distance) {
  for (int k = i * capacity_; k < i * capacity_ + degree_[i]; ++k)
    if (partners_[k] == j) {
      contact_[k] = distance;
      return;
    }
}

void EventFlight::relax_tolerated() {
  const bool listed = capacity_ > 0 && degree_.size() == size();
  for (auto it = tolerated_.begin(); it != tolerated_.end();) {
    const int i = static_cast<int>(it->first >> 32), j = static_cast<int>(it->first & 0xffffffffu);
    const double distance = norm(nearest(motion_[i].x - motion_[j].x)), sigma = radius[i] + radius[j];
    const bool parted = distance >= sigma, grown = !parted && distance > it->second;
    if (grown) it->second = distance;
    if (listed && (parted || grown)) {  // the listed entries hold the old distance
      set_listed_contact(i, j, parted ? sigma : it->second);
      set_listed_contact(j, i, parted ? sigma : it->second);
    }
    it = parted ? tolerated_.erase(it) : std::next(it);
  }
  for (std::size_t i = 0; i < size(); ++i)
    for (int a = 0; a < 3; ++a)
      for (int side = 0; side < 2; ++side) {
        double &reach = reach_[6 * i + 2 * a + side];
        if (reach >= radius[i]) continue;
        const Vec3 &x = motion_[i].x;
        const double gap = side == 0 ? x[a] - box_.lower[a] : box_.upper[a] - x[a];
        reach = std::min(radius[i], std::max(reach, gap));
      }
}

void EventFlight::predict(int i, double now, double end) {
  ++counts_.predictions;
  double best = end;
  int partner = std::numeric_limits<int>::min();
  const Motion &mi = motion_[i];
  const Vec3 xi = mi.x + (now - mi.t) * mi.v;
  const Vec3 &vi = mi.v;
  for (int k = i * capacity_; k < i * capacity_ + degree_[i]; ++k) {
    const int j = partners_[k];
    const Motion &mj = motion_[j];
    const Vec3 r = nearest(xi - (mj.x + (now - mj.t) * mj.v));
    const Vec3 u = vi - mj.v;
    const double b = dot(r, u);
    if (b >= 0) continue;  // moving apart
    const double sigma = contact_[k];
    const double c = dot(r, r) - sigma * sigma;
    double t = 0;  // touching or overlapping, and approaching: now
    if (c > 0) {
      if (c >= -2 * b * (best - now)) continue;  // t >= c / (-2 b): not before the best so far
      const double disc = b * b - dot(u, u) * c;
      if (disc <= 0) continue;  // they pass each other
      t = c / (-b + std::sqrt(disc));  // eq. 45
    }
    if (now + t < best) {
      best = now + t;
      partner = j;
    }
  }
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      if (!box_.wall[a][side] || box_.periodic[a]) continue;
      const double towards = side == 0 ? -vi[a] : vi[a];
      if (towards <= 0) continue;
      const double reach = reach_[6 * i + 2 * a + side];
      const double gap = side == 0 ? xi[a] - box_.lower[a] - reach : box_.upper[a] - xi[a] - reach;
      const double t = gap > 0 ? gap / towards : 0;
      if (now + t < best) {
        best = now + t;
        partner = -1 - (2 * a + side);
      }
    }
  {  // leaving the anchor's sphere: |d + v t| = skin / 2
    const Vec3 d = nearest(xi - anchor_[i]);
    const double vv = dot(vi, vi), b = dot(d, vi), c = dot(d, d) - 0.25 * skin_ * skin_;
    if (vv > 0) {
      const double root = std::sqrt(std::max(b * b - vv * c, 0.0));
      const double t = c >= 0 ? 0 : b > 0 ? -c / (b + root) : (root - b) / vv;
      if (now + t < best) {
        best = now + t;
        partner = kLeavesAnchor;
      }
    }
  }
  if (partner == std::numeric_limits<int>::min()) return;  // nothing before the step's end
  heap_.push_back({best, i, partner, count_[i], partner >= 0 ? count_[partner] : 0});
  std::push_heap(heap_.begin(), heap_.end(), std::greater<Event>());
}

FlightCounts EventFlight::fly(double dt) {
  counts_ = {};
  const int n = static_cast<int>(size());
  pack();
  count_.assign(n, 0);
  std::fill(impulse.begin(), impulse.end(), Vec3{});
  heap_.clear();
  if (lists_built_ && degree_.size() == size())
    relax_tolerated();
  else
    build_lists(0);
  for (int i = 0; i < n; ++i) predict(i, 0, dt);
  const long limit = max_collisions_per_particle_ * std::max(n, 1);
  const CollisionLaw elastic{1, 0, 0};  // TC model: elastic and smooth
  while (!heap_.empty()) {
    std::pop_heap(heap_.begin(), heap_.end(), std::greater<Event>());
    const Event e = heap_.back();
    heap_.pop_back();
    const int a = e.particle;
    if (count_[a] != e.count) continue;  // a collided since: its new event is in the heap
    if (e.partner >= 0 && count_[e.partner] != e.partner_count) {
      predict(a, e.time, dt);  // the partner collided since
      continue;
    }
    if (e.partner == kLeavesAnchor) {
      if (!renew_list(a, e.time)) {  // a list is full: all of them again, with more room
        build_lists(e.time);
        heap_.clear();
        for (int i = 0; i < n; ++i) predict(i, e.time, dt);
        continue;
      }
      predict(a, e.time, dt);
      continue;
    }
    advance_to(a, e.time);
    const double when = clock_ + e.time;
    Sphere sa{motion_[a].v, spin[a], radius[a], mass[a]};
    if (e.partner >= 0) {
      const int b = e.partner;
      advance_to(b, e.time);
      const Vec3 r = nearest(motion_[a].x - motion_[b].x);
      const bool tc = when - last_collision[a] < elastic_within_ || when - last_collision[b] < elastic_within_;
      Sphere sb{motion_[b].v, spin[b], radius[b], mass[b]};
      const Impulse j = collide(sa, sb, (1 / norm(r)) * r, tc ? elastic : law(a, b));
      motion_[b].v = sb.velocity, spin[b] = sb.spin;
      impulse[b] -= j.on_a;
      last_collision[b] = when;
      ++count_[b];
      ++counts_.pair;
      counts_.elastic += tc;
      motion_[a].v = sa.velocity, spin[a] = sa.spin;
      impulse[a] += j.on_a;
    } else {
      const int plane = -1 - e.partner, axis = plane / 2, side = plane % 2;
      Vec3 normal;
      normal[axis] = side == 0 ? 1 : -1;  // into the box
      const bool tc = when - last_collision[a] < elastic_within_;
      const Impulse j = collide_with_wall(sa, normal, tc ? elastic : wall_laws_[type[a]]);
      motion_[a].v = sa.velocity, spin[a] = sa.spin;
      impulse[a] += j.on_a;
      ++counts_.wall;
      counts_.elastic += tc;
    }
    last_collision[a] = when;
    ++count_[a];
    if (counts_.pair + counts_.wall > limit) {
      std::ostringstream what;
      what << "inelastic collapse: " << counts_.pair + counts_.wall << " collisions of " << n
           << " particles within one flow step of " << dt << " s (more than " << max_collisions_per_particle_
           << " a particle), at t = " << when << " s";
      throw std::runtime_error(what.str());
    }
    predict(a, e.time, dt);
    if (e.partner >= 0) predict(e.partner, e.time, dt);
  }
  for (int i = 0; i < n; ++i) advance_to(i, dt);
  unpack();
  clock_ += dt;
  return counts_;
}

}  // namespace tfdem::hard_sphere
