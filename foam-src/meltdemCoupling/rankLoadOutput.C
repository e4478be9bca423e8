#include "rankLoadOutput.H"

#include <sstream>
#include <string>
#include <vector>

namespace mc = ::meltdem::coupling;


Foam::meltdem::rankLoadOutput::rankLoadOutput
(
    const fvMesh& mesh,
    MPI_Comm comm,
    bool resumed
)
:
    mesh_(mesh),
    comm_(comm)
{
    if (!Pstream::master()) return;
    const fileName dir(mesh.time().globalPath()/"postProcessing"/"particleLedger");
    mkDir(dir);
    const fileName file(dir/"ranks.csv");
    const std::string header =
        "time,rank,cells,metal_cells,particles,located,visitors,weights,messages_sent,messages_received,"
        "bytes_sent,bytes_received";
    std::vector<std::string> kept{header};
    if (resumed)
    {
        // the rows of the steps up to the resumed run's start (a stopped run wrote past it)
        const double start = mesh.time().value();
        std::ifstream in(file);
        std::string line;
        std::getline(in, line);
        while (std::getline(in, line))
        {
            std::istringstream is(line);
            double t = 0;
            if (!(is >> t) || t > start*(1 + 1e-12)) break;
            kept.push_back(line);
        }
    }
    csv_.reset(new std::ofstream(file, std::ios::trunc));
    for (const auto& l : kept) *csv_ << l << '\n';
    csv_->flush();
}


void Foam::meltdem::rankLoadOutput::write
(
    std::int64_t metalCells,
    std::int64_t particles,
    std::initializer_list<const mc::ParallelExchange*> exchanges
)
{
    constexpr int kCounters = 10;
    std::int64_t mine[kCounters] = {};
    mine[0] = mesh_.nCells();
    mine[1] = metalCells;
    mine[2] = particles;
    for (const mc::ParallelExchange* e : exchanges)
    {
        const mc::ExchangeTraffic& t = e->traffic();
        const std::int64_t c[kCounters - 3] =
        {
            t.located, t.visitors, t.weights, t.messages_sent, t.messages_received,
            t.bytes_sent, t.bytes_received
        };
        for (int k = 0; k < kCounters - 3; ++k) mine[3 + k] += c[k];
        e->reset_traffic();
    }
    int rank = 0, size = 1;
    MPI_Comm_rank(comm_, &rank);
    MPI_Comm_size(comm_, &size);
    std::vector<std::int64_t> all(rank == 0 ? std::size_t(kCounters)*size : 0);
    MPI_Gather(mine, kCounters, MPI_INT64_T, all.data(), kCounters, MPI_INT64_T, 0, comm_);
    if (!csv_ || rank != 0) return;
    std::ostream& o = *csv_;
    o.precision(17);
    for (int r = 0; r < size; ++r)
    {
        o << mesh_.time().value() << ',' << r;
        for (int k = 0; k < kCounters; ++k) o << ',' << all[std::size_t(kCounters)*r + k];
        o << '\n';
    }
    o.flush();
}
