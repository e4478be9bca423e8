// parallel_exchange.h on one rank: the weights equal distribute_particle's, deposits sum
// to what was handed over, sampling equals sample_fluid.
#include "meltdem/coupling/parallel_exchange.h"
#include "parallel_exchange_case.h"
#include "validation_report.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

using namespace meltdem::coupling;
using namespace meltdem::coupling::testing;

class ParallelExchangeSerial : public ::testing::TestWithParam<DistributionModel> {};

TEST_P(ParallelExchangeSerial, WeightsEqualTheSerialDistribution)
{
  ExchangeCase k;
  const CartesianGridMesh mesh(k.x, k.y, k.z);
  ParallelExchange ex(mesh, GetParam(), MPI_COMM_SELF);
  ex.locate(k.particles);
  double worst = 0.0;
  int inside = 0;
  std::vector<CellWeight> ref, got;
  for (std::size_t i = 0; i < k.particles.size(); ++i) {
    const bool in = distribute_particle(mesh, GetParam(), k.particles[i].x, k.particles[i].radius, ref);
    ASSERT_EQ(in, ex.inside(i)) << "particle " << i;
    inside += in;
    ex.local_weights(std::int64_t(i), got);
    std::map<long, double> a, b;
    for (auto &w : ref) a[w.cell] += w.weight;
    for (auto &w : got) b[w.cell] += w.weight;
    ASSERT_EQ(a.size(), b.size()) << "particle " << i;
    for (auto &[cell, w] : a) worst = std::max(worst, std::abs(w - b.at(cell)));
  }
  EXPECT_GT(inside, 40);
  meltdem::testing::expect_absolute(std::string("parallel_exchange ") + to_string(GetParam()) +
                                        ": largest weight difference vs distribute_particle",
                                    worst, 0.0, 1e-14);
}

TEST_P(ParallelExchangeSerial, DepositSumsToWhatWasHandedOver)
{
  ExchangeCase k;
  const CartesianGridMesh mesh(k.x, k.y, k.z);
  ParallelExchange ex(mesh, GetParam(), MPI_COMM_SELF);
  ex.locate(k.particles);
  std::vector<Amounts> cells(std::size_t(mesh.n_cells()), Amounts{});
  ex.deposit(k.amounts, cells);
  // one value per particle deposits as the first component of the amounts
  std::vector<double> values, cell_values(std::size_t(mesh.n_cells()), 0.0);
  for (const Amounts &a : k.amounts) values.push_back(a[0]);
  ex.deposit(values, cell_values);
  for (std::size_t c = 0; c < cells.size(); ++c) EXPECT_EQ(cell_values[c], cells[c][0]) << "cell " << c;
  EXPECT_THROW(ex.deposit(std::vector<double>(3, 1.0), cell_values), std::invalid_argument);
  for (int q = 0; q < kComponents; ++q) {
    double handed = 0.0, got = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < k.amounts.size(); ++i) {
      if (ex.inside(i)) handed += k.amounts[i][q];
      scale = std::max(scale, std::abs(k.amounts[i][q]));
    }
    for (auto &c : cells) got += c[q];
    EXPECT_LE(std::abs(got - handed), 1e-14 * scale * k.amounts.size()) << "component " << q;
  }
}

TEST_P(ParallelExchangeSerial, WeightedMeanIsTheDepositsAdjoint)
{
  // sum_p a_p mean_p(f) = sum_c f_c deposit_c(a): the mean a particle sees through the weights
  // is exactly what the implicit heat exchange books against what its cells lost
  ExchangeCase k;
  const CartesianGridMesh mesh(k.x, k.y, k.z);
  ParallelExchange ex(mesh, GetParam(), MPI_COMM_SELF);
  ex.locate(k.particles);
  std::vector<double> f(std::size_t(mesh.n_cells()));
  for (std::size_t c = 0; c < f.size(); ++c) f[c] = 300.0 + 7.0 * double(c % 13) + 0.01 * double(c);
  std::vector<double> mean;
  ex.weighted_mean(f.data(), mean);
  ASSERT_EQ(mean.size(), k.particles.size());
  std::vector<Amounts> a(k.particles.size(), Amounts{}), cells(f.size(), Amounts{});
  double lhs = 0.0, rhs = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    a[i][0] = 1.0 + 0.1 * double(i);
    if (ex.inside(i))
      lhs += a[i][0] * mean[i];
    else
      EXPECT_EQ(mean[i], 0.0);
  }
  ex.deposit(a, cells);
  for (std::size_t c = 0; c < f.size(); ++c) rhs += f[c] * cells[c][0];
  meltdem::testing::expect_relative(std::string("parallel_exchange ") + to_string(GetParam()) +
                                        ": sum a mean(f) vs sum f deposit(a)",
                                    lhs, rhs, 1e-13);
}

TEST_P(ParallelExchangeSerial, SamplingEqualsSampleFluid)
{
  ExchangeCase k;
  const CartesianGridMesh mesh(k.x, k.y, k.z);
  std::vector<double> T, one, U;
  for (long c = 0; c < mesh.n_cells(); ++c) {
    T.push_back(ExchangeCase::field(mesh.cell_centre(c)));
    one.push_back(1.0);
    U.insert(U.end(), {1.0, 2.0, 3.0});
  }
  const CellFluidFields f{T.data(), one.data(), one.data(), one.data(), one.data(), U.data(), one.data(), nullptr};
  ParallelExchange ex(mesh, GetParam(), MPI_COMM_SELF);
  ex.locate(k.particles);
  std::vector<SampledFluid> got;
  ex.sample(f, got);
  std::vector<CellWeight> w;
  for (std::size_t i = 0; i < k.particles.size(); ++i) {
    if (!distribute_particle(mesh, GetParam(), k.particles[i].x, k.particles[i].radius, w)) continue;
    const SampledFluid ref = sample_fluid(w, f);
    EXPECT_NEAR(got[i].fluid.T, ref.fluid.T, 1e-12 * ref.fluid.T);
    EXPECT_NEAR(got[i].alpha_metal, 1.0, 1e-14);
    EXPECT_NEAR(got[i].fluid.U[2], 3.0, 1e-14);
  }
}

namespace {
// 8^3 unit cells, melt (2000 K, moving along x) below y = 4, gas (500 K, moving along y) above,
// and a particle of radius 1.6 on the interface (centre/overlap) or just below it (neighbours:
// its centre cell is metal)
struct MeltOverGas {
  CartesianGridMesh mesh = CartesianGridMesh::uniform(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(8, 8, 8), 8, 8, 8);
  std::vector<double> T, k, rho, mu, cp, U, V;
  MeltOverGas()
  {
    for (long c = 0; c < mesh.n_cells(); ++c) {
      const bool metal = mesh.cell_centre(c).y() < 4.0;
      T.push_back(metal ? 2000.0 : 500.0);
      k.push_back(metal ? 35.95 : 0.026);
      rho.push_back(metal ? 7430.0 : 7.43);
      cp.push_back(metal ? 965.0 : 10.0);
      mu.push_back(1e-3);
      U.insert(U.end(), {metal ? 1.0 : 0.0, metal ? 0.0 : 5.0, 0.0});
      V.push_back(1.0);
    }
  }
  // with_volume: cell volumes given (heat by each cell's heat beyond the particle's temperature)
  CellFluidFields fields(bool with_volume) const
  {
    return CellFluidFields{T.data(),  k.data(),  rho.data(),
                           mu.data(), cp.data(), U.data(),
                           nullptr,   nullptr,   with_volume ? V.data() : nullptr};
  }
  static ParticleShape particle(DistributionModel model)
  {
    return ParticleShape{Eigen::Vector3d(4.5, model == DistributionModel::Centre ? 3.5 : 4.0, 4.5), 1.6};
  }
};
}  // namespace

// A particle half in melt, half in gas (overlap, 4 cells across the interface): it sees the
// melt's temperature and velocity (capacity- and mass-weighted). Without cell volumes the
// heat and impulse it takes come from the cells by capacity and by mass, so the gas cells
// (1e-5 of the capacity, 1e-3 of the mass) give that fraction of their share by volume,
// every covered cell the same temperature and velocity change per covered volume, and the
// sums are exact.
TEST_P(ParallelExchangeSerial, HeatAndImpulseComeFromTheCellsByCapacityAndMass)
{
  const MeltOverGas scene;
  const auto &mesh = scene.mesh;
  const auto &T = scene.T;
  const double rhocp_metal = 7430.0 * 965.0, rhocp_gas = 7.43 * 10.0;
  const CellFluidFields f = scene.fields(false);
  ParallelExchange ex(mesh, GetParam(), MPI_COMM_SELF);
  ex.locate({MeltOverGas::particle(GetParam())});
  std::vector<SampledFluid> s;
  ex.sample(f, s);
  std::vector<CellWeight> w;
  ex.local_weights(0, w);
  double metal_w = 0.0, cap = 0.0, mass = 0.0;
  for (auto &cw : w) {
    const bool metal = T[cw.cell] > 1000.0;
    metal_w += metal ? cw.weight : 0.0;
    cap += cw.weight * (metal ? rhocp_metal : rhocp_gas);
    mass += cw.weight * (metal ? 7430.0 : 7.43);
  }
  EXPECT_NEAR(s[0].fluid.U[0], metal_w * 7430.0 / mass, 1e-12);
  EXPECT_NEAR(s[0].fluid.U[1], 5.0 * (1 - metal_w) * 7.43 / mass, 1e-12);
  const double expect_T = (metal_w * rhocp_metal * 2000.0 + (1 - metal_w) * rhocp_gas * 500.0) / cap;
  EXPECT_NEAR(s[0].fluid.T, expect_T, 1e-9 * expect_T);
  EXPECT_GT(s[0].fluid.T, 1999.9);  // the melt's, not the volume mean
  const double Q = 2.5e-6;
  const Eigen::Vector3d I(3e-9, -1e-9, 2e-9);
  std::vector<Amounts> cells(std::size_t(mesh.n_cells()), Amounts{});
  ex.deposit_taken({0}, {Q}, {I}, {1200.0}, f, cells);
  double taken = 0.0, from_gas = 0.0, impulse_x = 0.0;
  for (long c = 0; c < mesh.n_cells(); ++c) {
    taken -= cells[std::size_t(c)][kEnthalpy];
    impulse_x -= cells[std::size_t(c)][kMomX];
    if (T[std::size_t(c)] < 1000.0) from_gas -= cells[std::size_t(c)][kEnthalpy];
  }
  meltdem::testing::expect_relative(
      std::string("deposit_taken ") + to_string(GetParam()) + ": heat taken from the cells", taken, Q, 1e-14);
  meltdem::testing::expect_relative(std::string("deposit_taken ") + to_string(GetParam()) +
                                        ": impulse taken from the cells (x)",
                                    impulse_x, I.x(), 1e-14);
  // the gas's share: its capacity-weighted fraction
  EXPECT_NEAR(from_gas, Q * (1 - metal_w) * rhocp_gas / cap, 1e-12 * Q);
  if (metal_w < 1.0) EXPECT_LT(from_gas, 1e-4 * Q);
  // each covered cell: temperature and velocity change per covered volume fraction the same
  for (auto &cw : w) {
    const bool metal = T[cw.cell] > 1000.0;
    const double c = metal ? rhocp_metal : rhocp_gas, r = metal ? 7430.0 : 7.43;
    EXPECT_NEAR(-cells[std::size_t(cw.cell)][kEnthalpy] / (c * cw.weight), Q / cap, 1e-12 * Q / cap);
    EXPECT_NEAR(-cells[std::size_t(cw.cell)][kMomY] / (r * cw.weight), I.y() / mass, 1e-12 * std::abs(I.y()) / mass);
  }
  EXPECT_THROW(ex.deposit_taken({0}, {}, {}, {}, f, cells), std::invalid_argument);
  EXPECT_THROW(ex.deposit_taken({0}, {Q}, {I}, {}, f, cells), std::invalid_argument);
}

// With cell volumes the heat goes by what each cell holds beyond the particle's temperature:
// a grain at 1200 K between melt (2000 K) and gas (500 K) that takes heat takes it from the
// melt cells alone, each moved the same fraction of the way to 1200 K, and the cold gas gives
// nothing (the capacity split made it colder still: the pbf-point scene's -2400 K cells);
// one that gives heat gives it to the gas alone. Heat beyond the cells' room brings every
// cell to 1200 K and the rest goes by capacity. Sums exact in each case.
TEST_P(ParallelExchangeSerial, HeatComesFromTheCellsBeyondTheParticlesTemperature)
{
  const MeltOverGas scene;
  const auto &mesh = scene.mesh;
  const auto &T = scene.T, &rho = scene.rho, &cp = scene.cp, &V = scene.V;
  const CellFluidFields f = scene.fields(true);
  ParallelExchange ex(mesh, GetParam(), MPI_COMM_SELF);
  ex.locate({MeltOverGas::particle(GetParam())});
  std::vector<CellWeight> w;
  ex.local_weights(0, w);
  const double Tp = 1200.0;
  // the room of each covered cell on each side of Tp (the particle is alone: it claims
  // each covered cell's whole capacity)
  double room_hot = 0.0, room_cold = 0.0;
  for (auto &cw : w) {
    const double C = V[cw.cell] * rho[cw.cell] * cp[cw.cell];
    room_hot += C * std::max(T[cw.cell] - Tp, 0.0);
    room_cold += C * std::max(Tp - T[cw.cell], 0.0);
  }
  const std::string m = to_string(GetParam());
  for (const double Q : {0.4 * room_hot, -0.4 * room_cold, 1.5 * room_hot}) {
    std::vector<Amounts> cells(std::size_t(mesh.n_cells()), Amounts{});
    ex.deposit_taken({0}, {Q}, {Eigen::Vector3d::Zero()}, {Tp}, f, cells);
    double taken = 0.0, from_gas = 0.0, from_melt = 0.0;
    for (long c = 0; c < mesh.n_cells(); ++c) {
      taken -= cells[std::size_t(c)][kEnthalpy];
      (T[std::size_t(c)] < 1000.0 ? from_gas : from_melt) -= cells[std::size_t(c)][kEnthalpy];
    }
    const std::string what = Q > room_hot ? "beyond the room" : Q > 0 ? "taken" : "given";
    meltdem::testing::expect_relative("deposit_taken " + m + " by room, heat " + what + ": sum over the cells", taken,
                                      Q, 1e-13);
    if (Q < 0) {
      if (room_cold > 0) {
        EXPECT_EQ(from_melt, 0.0);
        meltdem::testing::expect_relative("deposit_taken " + m + " by room: heat given goes to the gas", from_gas, Q,
                                          1e-13);
      }
      continue;
    }
    if (Q <= room_hot) EXPECT_EQ(from_gas, 0.0) << "a gas cell colder than the particle gave heat";
    for (auto &cw : w) {
      const double C = V[cw.cell] * rho[cw.cell] * cp[cw.cell];
      const double dT_cell = cells[std::size_t(cw.cell)][kEnthalpy] / C;
      if (T[cw.cell] < Tp && Q <= room_hot) continue;
      if (Q <= room_hot)  // the same fraction of the way to Tp
        EXPECT_NEAR(dT_cell / (Tp - T[cw.cell]), Q / room_hot, 1e-12);
      else  // past Tp only by the capacity share of the rest
        EXPECT_LT(T[cw.cell] + dT_cell, Tp);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Models, ParallelExchangeSerial,
                         ::testing::Values(DistributionModel::Centre, DistributionModel::Neighbours,
                                           DistributionModel::Overlap),
                         [](const auto &info) { return std::string(to_string(info.param)); });

TEST(ParallelExchange, BadInputThrows)
{
  const auto mesh = CartesianGridMesh::uniform(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), 2, 2, 2);
  ParallelExchange ex(mesh, DistributionModel::Overlap, MPI_COMM_SELF);
  EXPECT_THROW(ex.locate({ParticleShape{Eigen::Vector3d(0.5, 0.5, 0.5), -1.0}}), std::invalid_argument);
  EXPECT_THROW(ex.locate({ParticleShape{Eigen::Vector3d(NAN, 0.5, 0.5), 0.1}}), std::invalid_argument);
  ex.locate({ParticleShape{Eigen::Vector3d(0.5, 0.5, 0.5), 0.1}});
  std::vector<Amounts> cells(8, Amounts{});
  EXPECT_THROW(ex.deposit({}, cells), std::invalid_argument);
}
