#include "tfdem/hard_sphere/event_flight.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace tfdem::hard_sphere {
namespace {

// A tolerated contact is taken a millionth of its distance closer than the spheres are (and a
// sphere sunk into a wall a millionth of its gap nearer the wall): touching at exactly their
// distance, a packing's network of contacts would collide at one instant without end once
// gravity moves the bed (every contact at zero gap, each collision closing the next); this gap
// puts the collisions at distinct times, which then run their course
constexpr double kToleratedGap = 1e-6;
// A particle list's room beyond the most partners found at a full build
constexpr int kSpareFraction = 2, kLeastSpare = 8;
// Below this many collisions a particle in a flow step, running out of them says the bound is
// low, not that the bed collapsed (the bubbling beds' lift measures up to some hundred)
constexpr long kFewCollisions = 1000;
// The event of leaving the anchor's sphere (walls are -1 ... -6)
constexpr int kLeavesAnchor = -7;

// Eq. 45: the time until a pair at separation r with relative velocity u touches at contact
// distance sigma, 0 when it touches or overlaps while approaching; infinite when it moves
// apart, passes by, or cannot touch within `horizon` (t >= c / (-2 b) bounds it from below).
inline double contact_time(const Vec3 &r, const Vec3 &u, double sigma, double horizon) {
  constexpr double kNever = std::numeric_limits<double>::infinity();
  const double b = dot(r, u);
  if (b >= 0) return kNever;  // moving apart
  const double c = dot(r, r) - sigma * sigma;
  if (c <= 0) return 0;
  if (c >= -2 * b * horizon) return kNever;
  const double disc = b * b - dot(u, u) * c;
  if (disc <= 0) return kNever;  // they pass each other
  return c / (-b + std::sqrt(disc));
}

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
  lists_.built = false;
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
  lists_.built = false;
}

void EventFlight::restore_tolerated(std::unordered_map<std::uint64_t, double> pairs, std::vector<double> reach) {
  if (reach.size() != 6 * size())
    throw std::invalid_argument("EventFlight::restore_tolerated: " + std::to_string(reach.size()) +
                                " wall reaches for " + std::to_string(size()) + " particles");
  tolerated_ = std::move(pairs);
  reach_ = std::move(reach);
  lists_.built = false;
}

void EventFlight::restore_lists(NeighbourLists lists) {
  const std::size_t n = size();
  std::size_t cells = 1;
  for (const int c : lists.cells) cells *= static_cast<std::size_t>(std::max(c, 0));
  const auto index_ok = [](const std::vector<int> &v, long high) {
    return std::all_of(v.begin(), v.end(), [high](int k) { return k >= -1 && k < high; });
  };
  const bool whole =
      !lists.built ||
      (lists.anchor.size() == n && lists.degree.size() == n && lists.capacity >= 0 &&
       lists.partners.size() == n * static_cast<std::size_t>(lists.capacity) &&
       lists.contact.size() == lists.partners.size() && lists.head.size() == cells && lists.next.size() == n &&
       lists.previous.size() == n && lists.cell.size() == n && index_ok(lists.partners, static_cast<long>(n)) &&
       index_ok(lists.head, static_cast<long>(n)) && index_ok(lists.next, static_cast<long>(n)) &&
       index_ok(lists.previous, static_cast<long>(n)) && index_ok(lists.cell, static_cast<long>(cells)) &&
       std::all_of(lists.degree.begin(), lists.degree.end(), [&](int d) { return d >= 0 && d <= lists.capacity; }));
  if (!whole)
    throw std::invalid_argument("EventFlight::restore_lists: the neighbour lists do not fit " + std::to_string(n) +
                                " particles");
  lists_ = std::move(lists);
}

EventFlight::Overlaps EventFlight::tolerate_overlaps() {
  Overlaps o;
  const int n = static_cast<int>(size());
  pack();
  build_lists(0);
  for (int i = 0; i < n; ++i) {
    for (int k = i * lists_.capacity; k < i * lists_.capacity + lists_.degree[i]; ++k) {
      const int j = lists_.partners[k];
      if (j <= i) continue;
      const double sigma = radius[i] + radius[j], distance = norm(nearest(position[i] - position[j]));
      if (distance >= sigma) continue;
      tolerated_[pair_key(i, j)] = distance * (1 - kToleratedGap);
      ++o.pairs;
      o.deepest = std::max(o.deepest, (sigma - distance) / (2 * std::min(radius[i], radius[j])));
    }
    for (int a = 0; a < 3; ++a)
      for (int side = 0; side < 2; ++side) {
        if (!box_.wall[a][side] || box_.periodic[a]) continue;
        const double gap = side == 0 ? position[i][a] - box_.lower[a] : box_.upper[a] - position[i][a];
        if (gap >= radius[i]) continue;
        reach_[6 * i + 2 * a + side] = std::max(gap * (1 - kToleratedGap), 0.0);
        ++o.walls;
        o.deepest = std::max(o.deepest, (radius[i] - gap) / (2 * radius[i]));
      }
  }
  lists_.built = false;  // built again with the contact distances
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
    c[a] = std::clamp(static_cast<int>(std::floor((x[a] - box_.lower[a]) / lists_.width[a])), 0, lists_.cells[a] - 1);
  return c[0] + lists_.cells[0] * (c[1] + lists_.cells[1] * c[2]);
}

void EventFlight::link(int i, int cell) {
  lists_.cell[i] = cell;
  lists_.previous[i] = -1;
  lists_.next[i] = lists_.head[cell];
  if (lists_.next[i] >= 0) lists_.previous[lists_.next[i]] = i;
  lists_.head[cell] = i;
}

void EventFlight::unlink(int i) {
  if (lists_.previous[i] >= 0) lists_.next[lists_.previous[i]] = lists_.next[i];
  else lists_.head[lists_.cell[i]] = lists_.next[i];
  if (lists_.next[i] >= 0) lists_.previous[lists_.next[i]] = lists_.previous[i];
}

double EventFlight::contact_distance(int i, int j) const {
  if (!tolerated_.empty()) {
    const auto found = tolerated_.find(pair_key(i, j));
    if (found != tolerated_.end()) return found->second;
  }
  return radius[i] + radius[j];
}

void EventFlight::gather(int i, std::vector<int> &out, std::vector<double> &contact) const {
  const int c = lists_.cell[i];
  const int ci[3] = {c % lists_.cells[0], (c / lists_.cells[0]) % lists_.cells[1], c / (lists_.cells[0] * lists_.cells[1])};
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        int cc[3] = {ci[0] + dx, ci[1] + dy, ci[2] + dz};
        bool inside = true;
        for (int a = 0; a < 3; ++a) {
          if (box_.periodic[a]) cc[a] = (cc[a] + lists_.cells[a]) % lists_.cells[a];
          inside = inside && cc[a] >= 0 && cc[a] < lists_.cells[a];
        }
        if (!inside) continue;
        for (int j = lists_.head[cc[0] + lists_.cells[0] * (cc[1] + lists_.cells[1] * cc[2])]; j >= 0; j = lists_.next[j]) {
          if (j == i) continue;
          const Vec3 r = nearest(lists_.anchor[i] - lists_.anchor[j]);
          const double within = radius[i] + radius[j] + lists_.skin;
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
  lists_.anchor.resize(n);
  for (int i = 0; i < n; ++i) {
    advance_to(i, now);
    lists_.anchor[i] = motion_[i].x;
    largest = std::max(largest, radius[i]);
  }
  lists_.built = true;
  if (n == 0) {  // a bed emptied through its outlets: no lists, no cells
    lists_.degree.clear();
    return;
  }
  lists_.skin = skin_diameters_ * 2 * largest;
  // cells at least as wide as the farthest reach of a listed pair's anchors
  const double reach = 2 * largest + lists_.skin;
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
      lists_.cells[a] = std::max(box_.periodic[a] ? 3 : 1, std::min(4096, static_cast<int>(span / cell_reach)));
      lists_.width[a] = span / lists_.cells[a];
      total *= lists_.cells[a];
    }
  }
  lists_.degree.clear();  // the old lists go: no contact distance to keep in them
  lists_.head.assign(total, -1);
  lists_.next.assign(n, -1);
  lists_.previous.assign(n, -1);
  lists_.cell.assign(n, 0);
  for (int i = n - 1; i >= 0; --i) link(i, cell_of(lists_.anchor[i]));  // each cell in index order
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
  lists_.capacity = most + std::max(kLeastSpare, most / kSpareFraction);
  lists_.partners.assign(static_cast<std::size_t>(n) * lists_.capacity, -1);
  lists_.contact.assign(static_cast<std::size_t>(n) * lists_.capacity, 0);
  lists_.degree.assign(n, 0);
  for (int i = 0; i < n; ++i) {
    lists_.degree[i] = first[i + 1] - first[i];
    std::copy(found.begin() + first[i], found.begin() + first[i + 1], lists_.partners.begin() + i * lists_.capacity);
    std::copy(contact.begin() + first[i], contact.begin() + first[i + 1], lists_.contact.begin() + i * lists_.capacity);
  }
}

bool EventFlight::renew_list(int i, double now) {
  ++counts_.lists_renewed;
  advance_to(i, now);
  lists_.anchor[i] = motion_[i].x;
  unlink(i);
  link(i, cell_of(lists_.anchor[i]));
  for (int k = i * lists_.capacity; k < i * lists_.capacity + lists_.degree[i]; ++k) {  // out of the old partners' lists
    const int j = lists_.partners[k], begin = j * lists_.capacity, end = begin + lists_.degree[j];
    for (int m = begin; m < end; ++m)
      if (lists_.partners[m] == i) {
        lists_.partners[m] = lists_.partners[end - 1];
        lists_.contact[m] = lists_.contact[end - 1];
        --lists_.degree[j];
        break;
      }
  }
  static thread_local std::vector<int> found;
  static thread_local std::vector<double> contact;
  found.clear();
  contact.clear();
  gather(i, found, contact);
  if (static_cast<int>(found.size()) > lists_.capacity) return false;
  for (std::size_t k = 0; k < found.size(); ++k) {
    const int j = found[k];
    if (lists_.degree[j] == lists_.capacity) return false;
    lists_.partners[j * lists_.capacity + lists_.degree[j]] = i;
    lists_.contact[j * lists_.capacity + lists_.degree[j]] = contact[k];
    ++lists_.degree[j];
    lists_.partners[i * lists_.capacity + k] = j;
    lists_.contact[i * lists_.capacity + k] = contact[k];
  }
  lists_.degree[i] = static_cast<int>(found.size());
  return true;
}

void EventFlight::set_listed_contact(int i, int j, double distance) {
  for (int k = i * lists_.capacity; k < i * lists_.capacity + lists_.degree[i]; ++k)
    if (lists_.partners[k] == j) {
      lists_.contact[k] = distance;
      return;
    }
}

void EventFlight::relax_tolerated() {
  const bool listed = lists_.capacity > 0 && lists_.degree.size() == size();
  for (auto it = tolerated_.begin(); it != tolerated_.end();) {
    const int i = static_cast<int>(it->first >> 32), j = static_cast<int>(it->first & 0xffffffffu);
    const double distance = norm(nearest(motion_[i].x - motion_[j].x)), sigma = radius[i] + radius[j];
    const double closer = distance * (1 - kToleratedGap);
    const bool parted = closer >= sigma, grown = !parted && closer > it->second;
    if (grown) it->second = closer;
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
        reach = std::min(radius[i], std::max(reach, gap * (1 - kToleratedGap)));
      }
}

void EventFlight::predict(int i, double now, double end) {
  ++counts_.predictions;
  double best = end;
  int partner = std::numeric_limits<int>::min();
  const Motion &mi = motion_[i];
  const Vec3 xi = mi.x + (now - mi.t) * mi.v;
  const Vec3 &vi = mi.v;
  for (int k = i * lists_.capacity; k < i * lists_.capacity + lists_.degree[i]; ++k) {
    const int j = lists_.partners[k];
    const Motion &mj = motion_[j];
    const Vec3 r = nearest(xi - (mj.x + (now - mj.t) * mj.v));
    const double t = contact_time(r, vi - mj.v, lists_.contact[k], best - now);
    if (now + t < best) {
      best = now + t;
      partner = j;
    }
  }
  predict_boundaries(i, xi, vi, now, best, partner);
  if (partner == std::numeric_limits<int>::min()) return;  // nothing before the step's end
  push_event(i, best, partner);
}

void EventFlight::predict_boundaries(int i, const Vec3 &xi, const Vec3 &vi, double now, double &best,
                                     int &partner) const {
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
  // leaving the anchor's sphere: |d + v t| = skin / 2, not before (skin/2 - |d|) / |v| >=
  // ((skin/2)^2 - |d|^2) / (skin |v|): when that is past `best`, no root is needed
  const Vec3 d = nearest(xi - lists_.anchor[i]);
  const double vv = dot(vi, vi), b = dot(d, vi), c = dot(d, d) - 0.25 * lists_.skin * lists_.skin;
  const double least = -c / lists_.skin;
  if (c < 0 && least * least >= vv * (best - now) * (best - now)) return;
  if (vv > 0) {
    const double root = std::sqrt(std::max(b * b - vv * c, 0.0));
    const double t = c >= 0 ? 0 : b > 0 ? -c / (b + root) : (root - b) / vv;
    if (now + t < best) {
      best = now + t;
      partner = kLeavesAnchor;
    }
  }
}

void EventFlight::push_event(int i, double time, int partner) {
  heap_.push_back(event_of(i, time, partner));
  std::push_heap(heap_.begin(), heap_.end(), std::greater<Event>());
}

void EventFlight::predict_all(double now, double end) {
  const int n = static_cast<int>(size());
  counts_.predictions += n;
  now_position_.resize(n);
  for (int i = 0; i < n; ++i) now_position_[i] = motion_[i].x + (now - motion_[i].t) * motion_[i].v;
  best_time_.assign(n, end);
  best_partner_.assign(n, std::numeric_limits<int>::min());
  for (int i = 0; i < n; ++i) {
    const Vec3 &xi = now_position_[i], &vi = motion_[i].v;
    for (int k = i * lists_.capacity; k < i * lists_.capacity + lists_.degree[i]; ++k) {
      const int j = lists_.partners[k];
      if (j < i) continue;  // the pair's time was found from j's list
      const double later = std::max(best_time_[i], best_time_[j]);  // past both partners' best: no use
      const Vec3 r = nearest(xi - now_position_[j]);
      const double t = contact_time(r, vi - motion_[j].v, lists_.contact[k], later - now);
      if (now + t < best_time_[i]) best_time_[i] = now + t, best_partner_[i] = j;
      if (now + t < best_time_[j]) best_time_[j] = now + t, best_partner_[j] = i;
    }
  }
  // the queue is empty here (a new flow step, or all lists rebuilt): filled, then made a heap
  // in one O(N) pass (at most 3N comparisons), not by N pushes (O(N log N) at worst)
  for (int i = 0; i < n; ++i) {
    predict_boundaries(i, now_position_[i], motion_[i].v, now, best_time_[i], best_partner_[i]);
    if (best_partner_[i] != std::numeric_limits<int>::min()) heap_.push_back(event_of(i, best_time_[i], best_partner_[i]));
  }
  std::make_heap(heap_.begin(), heap_.end(), std::greater<Event>());
}

std::string EventFlight::collapse(int n, double dt, double when, double last_half) const {
  std::ostringstream what;
  what << counts_.pair + counts_.wall << " collisions of " << n << " particles within one flow step of " << dt
       << " s, more than dem.hard_sphere.max_collisions_per_particle (" << max_collisions_per_particle_
       << ") a particle, at t = " << when << " s";
  if (last_half <= 1e-9 * dt)
    what << "; the last half of them at one instant (within " << last_half << " s): a network of spheres "
         << "colliding at zero gap, each collision closing the next, without end (spheres placed exactly "
         << "touching, or a packing whose contacts were edited). Fix: leave gaps between the spheres, or pour "
         << "the bed with tfdem pack";
  else
    what << ": inelastic collapse (seed 001 sec. 2.1), collision rates diverging in a dense cluster. Fix: a "
         << "longer TC time (dem.hard_sphere.elastic_within, now " << elastic_within_ << " s) keeps clusters "
         << "from collapsing; or run the bed with dem.engine: liggghts (soft spheres)"
         << (max_collisions_per_particle_ < kFewCollisions
                 ? "; or, if the bed is only busy, a higher max_collisions_per_particle (a bubbling bed's spheres "
                   "collide up to some hundred times in a flow step as it lifts)"
                 : "");
  return what.str();
}

FlightCounts EventFlight::fly(double dt) {
  counts_ = {};
  const int n = static_cast<int>(size());
  pack();
  count_.assign(n, 0);
  std::fill(impulse.begin(), impulse.end(), Vec3{});
  heap_.clear();
  if (lists_.built && lists_.degree.size() == size())
    relax_tolerated();
  else
    build_lists(0);
  predict_all(0, dt);
  const long limit = max_collisions_per_particle_ * std::max(n, 1);
  double halfway = -1;  // when half the limit was reached: tells a cascade at one instant
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
        predict_all(e.time, dt);
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
      const Impulse j = collide(sa, sb, (1 / norm(r)) * r, tc ? tc_law(law(a, b)) : law(a, b));
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
      const Impulse j = collide_with_wall(sa, normal, tc ? tc_law(wall_laws_[type[a]]) : wall_laws_[type[a]]);
      motion_[a].v = sa.velocity, spin[a] = sa.spin;
      impulse[a] += j.on_a;
      ++counts_.wall;
      counts_.elastic += tc;
    }
    last_collision[a] = when;
    ++count_[a];
    if (halfway < 0 && counts_.pair + counts_.wall >= limit / 2) halfway = e.time;
    if (counts_.pair + counts_.wall > limit) throw std::runtime_error(collapse(n, dt, when, e.time - halfway));
    predict(a, e.time, dt);
    if (e.partner >= 0) predict(e.partner, e.time, dt);
  }
  for (int i = 0; i < n; ++i) advance_to(i, dt);
  unpack();
  clock_ += dt;
  return counts_;
}

}  // namespace tfdem::hard_sphere
