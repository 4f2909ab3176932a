// Fetches aligned sets from a running alignset-server through the installed
// client library:  alignset_consumer HOST:PORT
// Exit status 0 when every check holds; otherwise one line on stderr.
#include <alignset/client.h>
#include <alignset/lattice_points.h>
#include <alignset/npy.h>
#include <alignset/aligned_sampler.h>
#include <alignset/set_choice.h>
#include <alignset/pixel_shift.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <string>
#include <vector>

#include <unistd.h>

namespace {

int Fail(const std::string& what) {
  std::fprintf(stderr, "alignset_consumer: %s\n", what.c_str());
  return 1;
}

bool InUnitSquare(const alignset::PointSet& points) {
  for (const alignset::Point2& p : points) {
    if (!(p.x >= 0 && p.x < 1 && p.y >= 0 && p.y < 1)) return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) return Fail("usage: alignset_consumer HOST:PORT");
  alignset::ConnectOptions options;
  options.address = argv[1];
  auto client = alignset::ServiceClient::Connect(options);
  if (!client.ok()) return Fail(client.status().ToString());

  // One set, with a deadline of its own.
  alignset::CallOptions call;
  call.timeout_seconds = 60;
  auto set = (*client)->GetAlignedSet(64, {30.0}, call);
  if (!set.ok()) return Fail("GetAlignedSet: " + set.status().ToString());
  if (set->points.size() != 64 || !InUnitSquare(set->points) || set->info.served_deg.size() != 1 ||
      set->info.served_deg[0] != 30) {
    return Fail("GetAlignedSet returned the wrong set");
  }

  // A batch: two good items and a bad one, each with its own status.
  auto batch = (*client)->GetAlignedSets({{64, {30.0}}, {64, {120.0}}, {8, {30.0}}}, call);
  if (!batch.ok()) return Fail("GetAlignedSets: " + batch.status().ToString());
  if (batch->size() != 3 || !(*batch)[0].status.ok() || !(*batch)[1].status.ok() ||
      (*batch)[2].status.code() != alignset::Status::Code::kInvalidArgument) {
    return Fail("GetAlignedSets: wrong item statuses");
  }
  if ((*batch)[0].set.raw != set->raw || !(*batch)[1].set.info.swapped) {
    return Fail("GetAlignedSets: wrong sets");
  }
  // The per-pixel recipe from the installed header: shifted sets stay in
  // the unit square, and two pixels get different shifts.
  alignset::PointSet shifted;
  for (const alignset::Point2& p : set->points) {
    shifted.push_back(alignset::ShiftPoint(p, alignset::PixelShift(7, 3, 4)));
  }
  if (!InUnitSquare(shifted) || alignset::PixelShift(7, 3, 4) == alignset::PixelShift(7, 4, 3)) {
    return Fail("PixelShift / ShiftPoint misbehave");
  }
  // A served tent-lattice tells its generator, and a pixel's own shift goes
  // before the fold: the sampler library's points for it
  // (<alignset/lattice_points.h>, SetPixelPoints of <alignset/aligned_sampler.h>).
  alignset::SetRequest tent_request;
  tent_request.n = 64;
  tent_request.directions_deg = {120.0};
  tent_request.construction = "tent-lattice";
  auto tent = (*client)->GetAlignedSet(tent_request, call);
  if (!tent.ok()) return Fail("GetAlignedSet tent-lattice: " + tent.status().ToString());
  const uint32_t g = tent->info.lattice_generator;
  const alignset::PointSet own =
      alignset::ShiftedLatticePoints(64, g, alignset::PixelShift(7, 3, 4), true);
  // The sampler library's pixel points of the same lattice: another shift of
  // it (realization 0's, then the pixel's), so unfolded they differ from
  // ShiftedLatticePoints' by one constant torus shift.
  alignset::TableSet served;
  served.n = tent->info.n;
  served.lattice_generator = g;
  alignset::PointSet library(64), folded(64);
  alignset::SetPixelPoints(served, alignset::PixelShift(7, 3, 4), library);
  served.folded = true;
  alignset::SetPixelPoints(served, alignset::PixelShift(7, 3, 4), folded);
  const alignset::PointSet unfolded = alignset::ShiftedLatticePoints(64, g, alignset::PixelShift(7, 3, 4), false);
  auto wrap = [](double d) { return d - std::floor(d); };
  bool one_shift = true;
  for (size_t i = 0; i < 64; ++i) {
    const double dx = wrap(library[i].x - unfolded[i].x - (library[0].x - unfolded[0].x) + 0.5) - 0.5;
    const double dy = wrap(library[i].y - unfolded[i].y - (library[0].y - unfolded[0].y) + 0.5) - 0.5;
    one_shift = one_shift && std::fabs(dx) < 1e-9 && std::fabs(dy) < 1e-9;
  }
  if (g == 0 || std::gcd(g, 64u) != 1 || own.size() != 64 || !InUnitSquare(own) || !InUnitSquare(folded) ||
      !one_shift) {
    return Fail("tent-lattice generator / ShiftedLatticePoints / SetPixelPoints misbehave");
  }
  // The set choice of the recipe (<alignset/set_choice.h>): 150.4 deg
  // and 29.6 deg are served as 150 and 30, a pair of non-axis directions; its
  // request is answered with that pair.
  const alignset::SetChoice two =
      alignset::ChooseSet({2, 150.4, 29.6 + 180.0}, alignset::AlignedPolicy{});
  const alignset::SetChoice axis = alignset::ChooseSet({2, 40.0, 90.2}, alignset::AlignedPolicy{});
  if (two.kind != alignset::SetChoice::Kind::kTwo || two.a != 30 || two.b != 150 ||
      axis.kind != alignset::SetChoice::Kind::kOne || axis.a != 40 ||
      alignset::ServedDegree(179.5) != 0 || alignset::AxialDistanceDeg(10.0, 170.0) != 20.0) {
    return Fail("ChooseSet / ServedDegree misbehave");
  }
  alignset::SetRequest pair_request;
  pair_request.n = 64;
  pair_request.directions_deg = {static_cast<double>(two.a), static_cast<double>(two.b)};
  auto pair = (*client)->GetAlignedSet(pair_request, call);
  if (!pair.ok() || pair->info.served_deg.size() != 2) {
    return Fail("GetAlignedSet for a recipe's pair: " +
                (pair.ok() ? std::string("wrong directions") : pair.status().ToString()));
  }
  // The .npy writer and reader: the set as an (N, 2) array, back unchanged.
  const std::string npy = std::string(std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp") +
                          "/alignset_consumer_" + std::to_string(::getpid()) + ".npy";
  std::vector<double> xy;
  for (const alignset::Point2& p : set->points) xy.insert(xy.end(), {p.x, p.y});
  const alignset::Status wrote = alignset::WriteNpy(npy, {set->points.size(), 2}, xy);
  auto read = alignset::ReadNpy(npy);
  std::remove(npy.c_str());
  if (!wrote.ok() || !read.ok() || read->values != xy ||
      read->shape != std::vector<size_t>{set->points.size(), 2}) {
    return Fail("WriteNpy / ReadNpy do not round-trip a set");
  }
  std::printf("alignset %s client: %zu points for %d deg (key %s), batch of %zu\n",
              alignset::kClientVersion, set->points.size(), set->info.served_deg[0],
              set->info.key_text.c_str(), batch->size());
  return 0;
}
