#include "tfdem/hard_sphere/event_flight.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace tfdem::hard_sphere {
namespace {

// The slowest speed the neighbour lists allow for (m/s): a bed at rest still gets the flow
// step's kick of gravity, and its lists must not be rebuilt on the first touch
constexpr double kLeastAllowedSpeed = 0.01;
// A listed partner's speed may reach this many times the fastest particle's before the lists
// are rebuilt (eq. 44's 2 v_max is the closing speed of two particles at v_max)
constexpr double kSpeedAllowance = 1.5;
// The least skin, in largest diameters: lists that serve several flow steps of a slow bed
constexpr double kSkinDiameters = 0.25;

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
  time_.assign(n, 0);
  path_.assign(n, 0);
  build_lists(0, 0);
  for (int i = 0; i < n; ++i) {
    for (int k = first_[i]; k < first_[i + 1]; ++k) {
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

void EventFlight::advance_to(int i, double t) {
  const double dt = t - time_[i];
  position[i] += dt * velocity[i];
  path_[i] += dt * norm(velocity[i]);
  time_[i] = t;
  if (!periodic_) return;
  for (int a = 0; a < 3; ++a)
    if (box_.periodic[a]) {
      const double span = box_.upper[a] - box_.lower[a];
      position[i][a] -= span * std::floor((position[i][a] - box_.lower[a]) / span);
    }
}

Vec3 EventFlight::nearest(Vec3 r) const {
  if (!periodic_) return r;
  for (int a = 0; a < 3; ++a)
    if (box_.periodic[a]) {
      const double span = box_.upper[a] - box_.lower[a];
      if (r[a] > 0.5 * span) r[a] -= span;
      else if (r[a] < -0.5 * span) r[a] += span;
    }
  return r;
}

bool EventFlight::lists_hold(double dt, double allowed) const {
  if (!lists_built_ || first_.size() != size() + 1) return false;
  double longest = 0, second = 0;
  for (const double p : path_) {
    if (p > longest) {
      second = longest;
      longest = p;
    } else if (p > second) {
      second = p;
    }
  }
  return longest + second + 2 * allowed * dt < skin_;
}

void EventFlight::build_lists(double now, double end) {
  ++counts_.list_builds;
  const int n = static_cast<int>(size());
  double fastest = 0, largest = 0;
  for (int i = 0; i < n; ++i) {
    advance_to(i, now);
    fastest = std::max(fastest, norm(velocity[i]));
    largest = std::max(largest, radius[i]);
  }
  path_.assign(n, 0);
  lists_built_ = true;
  allowed_speed_ = std::max(kSpeedAllowance * fastest, kLeastAllowedSpeed);
  skin_ = std::max(2 * allowed_speed_ * (end - now), kSkinDiameters * 2 * largest);
  const double skin = skin_;
  // cells at least as wide as the farthest reach of a listed pair
  const double reach = 2 * largest + skin;
  int cells[3];
  double width[3];
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
      cells[a] = std::max(box_.periodic[a] ? 3 : 1, std::min(4096, static_cast<int>(span / cell_reach)));
      width[a] = span / cells[a];
      total *= cells[a];
    }
  }
  const auto cell_of = [&](const Vec3 &x, int a) {
    return std::clamp(static_cast<int>(std::floor((x[a] - box_.lower[a]) / width[a])), 0, cells[a] - 1);
  };
  std::vector<int> start(total + 1, 0), items(n), cell(n);
  for (int i = 0; i < n; ++i) {
    cell[i] = cell_of(position[i], 0) + cells[0] * (cell_of(position[i], 1) + cells[1] * cell_of(position[i], 2));
    ++start[cell[i] + 1];
  }
  for (int c = 0; c < total; ++c) start[c + 1] += start[c];
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int i = 0; i < n; ++i) items[fill[cell[i]]++] = i;
  }
  first_.assign(n + 1, 0);
  partners_.clear();
  contact_.clear();
  // tolerated overlaps: the contact distance grows to the present distance as the pair parts;
  // those that have parted are forgotten; the same for the spheres' reach towards the walls
  for (auto it = tolerated_.begin(); it != tolerated_.end();) {
    const int i = static_cast<int>(it->first >> 32), j = static_cast<int>(it->first & 0xffffffffu);
    const double distance = norm(nearest(position[i] - position[j]));
    if (distance >= radius[i] + radius[j]) {
      it = tolerated_.erase(it);
    } else {
      it->second = std::max(it->second, distance);
      ++it;
    }
  }
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a)
      for (int side = 0; side < 2; ++side) {
        double &reach = reach_[6 * i + 2 * a + side];
        if (reach >= radius[i]) continue;
        const double gap = side == 0 ? position[i][a] - box_.lower[a] : box_.upper[a] - position[i][a];
        reach = std::min(radius[i], std::max(reach, gap));
      }
  for (int i = 0; i < n; ++i) {
    const int ci[3] = {cell[i] % cells[0], (cell[i] / cells[0]) % cells[1], cell[i] / (cells[0] * cells[1])};
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          int cc[3] = {ci[0] + dx, ci[1] + dy, ci[2] + dz};
          bool inside = true;
          for (int a = 0; a < 3; ++a) {
            if (box_.periodic[a]) cc[a] = (cc[a] + cells[a]) % cells[a];
            inside = inside && cc[a] >= 0 && cc[a] < cells[a];
          }
          if (!inside) continue;
          const int c = cc[0] + cells[0] * (cc[1] + cells[1] * cc[2]);
          for (int k = start[c]; k < start[c + 1]; ++k) {
            const int j = items[k];
            if (j == i) continue;
            const Vec3 r = nearest(position[i] - position[j]);
            const double within = radius[i] + radius[j] + skin;
            if (dot(r, r) >= within * within) continue;
            partners_.push_back(j);
            double sigma = radius[i] + radius[j];
            if (!tolerated_.empty()) {
              const auto found = tolerated_.find(pair_key(i, j));
              if (found != tolerated_.end()) sigma = found->second;
            }
            contact_.push_back(sigma);
          }
        }
    first_[i + 1] = static_cast<int>(partners_.size());
  }
}

void EventFlight::predict(int i, double now, double end) {
  ++counts_.predictions;
  double best = end;
  int partner = std::numeric_limits<int>::min();
  const Vec3 xi = position[i] + (now - time_[i]) * velocity[i];
  const Vec3 &vi = velocity[i];
  for (int k = first_[i]; k < first_[i + 1]; ++k) {
    const int j = partners_[k];
    const Vec3 r = nearest(xi - (position[j] + (now - time_[j]) * velocity[j]));
    const Vec3 u = vi - velocity[j];
    const double b = dot(r, u);
    if (b >= 0) continue;  // moving apart
    const double sigma = contact_[k];
    const double c = dot(r, r) - sigma * sigma;
    double t = 0;  // touching or overlapping, and approaching: now
    if (c > 0) {
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
  if (partner == std::numeric_limits<int>::min()) return;  // nothing before the step's end
  heap_.push_back({best, i, partner, count_[i], partner >= 0 ? count_[partner] : 0});
  std::push_heap(heap_.begin(), heap_.end(), std::greater<Event>());
}

FlightCounts EventFlight::fly(double dt) {
  counts_ = {};
  const int n = static_cast<int>(size());
  time_.assign(n, 0);
  count_.assign(n, 0);
  path_.resize(n, 0);
  std::fill(impulse.begin(), impulse.end(), Vec3{});
  heap_.clear();
  double fastest = 0;
  for (const Vec3 &v : velocity) fastest = std::max(fastest, norm(v));
  const double allowed = std::max(kSpeedAllowance * fastest, kLeastAllowedSpeed);
  if (lists_hold(dt, allowed))
    allowed_speed_ = allowed;
  else
    build_lists(0, dt);
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
    advance_to(a, e.time);
    const double when = clock_ + e.time;
    Sphere sa{velocity[a], spin[a], radius[a], mass[a]};
    if (e.partner >= 0) {
      const int b = e.partner;
      advance_to(b, e.time);
      const Vec3 r = nearest(position[a] - position[b]);
      const bool tc = when - last_collision[a] < elastic_within_ || when - last_collision[b] < elastic_within_;
      Sphere sb{velocity[b], spin[b], radius[b], mass[b]};
      const Impulse j = collide(sa, sb, (1 / norm(r)) * r, tc ? elastic : law(a, b));
      velocity[b] = sb.velocity, spin[b] = sb.spin;
      impulse[b] -= j.on_a;
      last_collision[b] = when;
      ++count_[b];
      ++counts_.pair;
      counts_.elastic += tc;
      velocity[a] = sa.velocity, spin[a] = sa.spin;
      impulse[a] += j.on_a;
    } else {
      const int plane = -1 - e.partner, axis = plane / 2, side = plane % 2;
      Vec3 normal;
      normal[axis] = side == 0 ? 1 : -1;  // into the box
      const bool tc = when - last_collision[a] < elastic_within_;
      const Impulse j = collide_with_wall(sa, normal, tc ? elastic : wall_laws_[type[a]]);
      velocity[a] = sa.velocity, spin[a] = sa.spin;
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
    const bool faster = norm(velocity[a]) > allowed_speed_ || (e.partner >= 0 && norm(velocity[e.partner]) > allowed_speed_);
    if (faster) {  // a listed partner set no longer bounds who it can reach: lists again
      build_lists(e.time, dt);
      heap_.clear();
      for (int i = 0; i < n; ++i) predict(i, e.time, dt);
      continue;
    }
    predict(a, e.time, dt);
    if (e.partner >= 0) predict(e.partner, e.time, dt);
  }
  for (int i = 0; i < n; ++i) advance_to(i, dt);
  clock_ += dt;
  return counts_;
}

}  // namespace tfdem::hard_sphere
