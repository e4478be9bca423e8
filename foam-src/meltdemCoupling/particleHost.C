#include "particleHost.H"

#include "uniformDimensionedFields.H"
#include "meltdem/coupling/parallel_exchange.h"

#include <limits>

namespace mc = ::meltdem::coupling;

namespace
{

Foam::word requiredWord(const Foam::dictionary& d, const Foam::word& key)
{
    if (!d.found(key))
    {
        FatalIOErrorInFunction(d)
            << "missing entry '" << key << "' in " << d.name() << Foam::exit(Foam::FatalIOError);
    }
    return d.get<Foam::word>(key);
}


// the particles hand over cp Tm + L per kilogram (Codina2019 eq. 2.9); the continuum must read
// that as liquid metal at Tm, so both sides need the same material
void checkMaterial
(
    const ::meltdem::LammpsCouplingHost& lammps,
    const Foam::dictionary& meltdemDict,
    const bool thermal
)
{
    using namespace Foam;
    const mc::MeltMaterial& p = lammps.material();
    if (!thermal)
    {
        // without the energy equation the continuum has no T, k, cp for the particles'
        // heating (eq. 2.13) and no solid metal: the particles are isothermal and exchange
        // momentum only (binder jetting: a liquid binder, no phase change)
        if (lammps.solid_metal_wall())
        {
            FatalIOErrorInFunction(meltdemDict.subDict("physics"))
                << "fix " << lammps.melt_fix_id() << " powder/melt keyword solid_metal "
                << "needs 'energy on': without the energy equation there is no solid metal"
                << exit(FatalIOError);
        }
        Info<< "Particles: energy off, isothermal particles (drag and buoyancy only: "
            << "no heat exchange, no melting)" << endl;
        return;
    }
    const dictionary& md = meltdemDict.subDict("metal");
    const scalar cp = md.get<scalar>("cp"), L = md.get<scalar>("L");
    const scalar Ts = md.get<scalar>("Tsolidus"), Tl = md.get<scalar>("Tliquidus");
    if (mag(p.cp - cp) > 1e-9*cp)
    {
        FatalIOErrorInFunction(md)
            << "cp " << cp << " differs from fix " << lammps.melt_fix_id()
            << " powder/melt cp " << p.cp << ": particles and melt must be the same metal"
            << exit(FatalIOError);
    }
    if (mag(p.latent - L) > 1e-9*max(L, SMALL))
    {
        FatalIOErrorInFunction(md)
            << "L " << L << " differs from fix " << lammps.melt_fix_id()
            << " powder/melt latent " << p.latent << exit(FatalIOError);
    }
    if (p.Tmelt < Ts - 1e-9 || p.Tmelt > Tl + 1e-9)
    {
        FatalIOErrorInFunction(md)
            << "fix " << lammps.melt_fix_id() << " powder/melt Tmelt " << p.Tmelt
            << " is outside [Tsolidus, Tliquidus] = [" << Ts << ", " << Tl << "]"
            << exit(FatalIOError);
    }
}


// the LAMMPS box contains the mesh (equal along periodic directions), every particle starts
// inside the mesh
void checkDomains
(
    const ::meltdem::LammpsCouplingHost& lammps,
    const Foam::meltdem::foamDistributionMesh& distMesh,
    const Foam::dictionary& dict,
    MPI_Comm comm
)
{
    using namespace Foam;
    const boundBox mb(distMesh.globalBounds());
    double lo[3], hi[3];
    int periodic[3];
    lammps.box(lo, hi, periodic);
    const scalar tol = 1e-9*mag(mb.span());
    const char* axis = "xyz";
    for (direction d = 0; d < 3; ++d)
    {
        const bool covers = lo[d] <= mb.min()[d] + tol && hi[d] >= mb.max()[d] - tol;
        const bool equal = mag(lo[d] - mb.min()[d]) <= tol && mag(hi[d] - mb.max()[d]) <= tol;
        if (!covers || (periodic[d] && !equal))
        {
            FatalIOErrorInFunction(dict)
                << "mismatched domains: the LAMMPS box in " << axis[d] << " is ["
                << lo[d] << ", " << hi[d] << "], the mesh spans [" << mb.min()[d]
                << ", " << mb.max()[d] << "]. The box must contain the mesh (particles "
                << "leaving the mesh are booked as outflow before LAMMPS could lose "
                << "them) and equal it along periodic directions"
                << exit(FatalIOError);
        }
    }

    std::vector<mc::ExchangeRecord> now;
    lammps.local_particles(now);
    std::vector<mc::ParticleShape> shapes;
    for (const auto& r : now) shapes.push_back({r.x, r.radius, r.id});
    mc::ParallelExchange probe(distMesh, mc::DistributionModel::Centre, comm);
    probe.locate(shapes);
    // the lowest id outside, on every rank
    std::int64_t outside = std::numeric_limits<std::int64_t>::max();
    for (std::size_t i = 0; i < shapes.size(); ++i)
    {
        if (!probe.inside(i)) outside = std::min(outside, shapes[i].id);
    }
    MPI_Allreduce(MPI_IN_PLACE, &outside, 1, MPI_INT64_T, MPI_MIN, comm);
    if (outside != std::numeric_limits<std::int64_t>::max())
    {
        FatalIOErrorInFunction(dict)
            << "particle " << outside << " of " << dict.get<word>("lammpsInput")
            << " is outside the mesh at the start; move it inside or enlarge the mesh"
            << exit(FatalIOError);
    }
}


// Particles (buoyancy, eq. 2.14, and fix gravity) and the continuum (hydrostatics) must feel
// the same gravity: the impulse the particles take from the fluid is the fluid's to lose.
void checkGravity
(
    const Foam::fvMesh& mesh,
    const ::meltdem::LammpsCouplingHost& lammps,
    const Foam::dictionary& dict
)
{
    using namespace Foam;
    double gl[3];
    lammps.gravity(gl);
    const vector gLammps(gl[0], gl[1], gl[2]);
    // meltdemFoam registers g on Time (meshObjects::gravity)
    vector gFoam(Zero);
    if (mesh.time().foundObject<uniformDimensionedVectorField>("g"))
    {
        gFoam = mesh.time().lookupObject<uniformDimensionedVectorField>("g").value();
    }
    if (mag(gLammps - gFoam) > 1e-9*max(mag(gLammps), mag(gFoam)))
    {
        FatalIOErrorInFunction(dict)
            << "mismatched gravity: the fix gravity of " << dict.get<word>("lammpsInput")
            << " gives " << gLammps << " m/s2, constant/g is " << gFoam
            << ": particles and continuum must feel the same gravity" << exit(FatalIOError);
    }
}

} // End anonymous namespace


Foam::meltdem::particleHost::particleHost
(
    const fvMesh& mesh,
    const dictionary& meltdemDict,
    const dictionary& dict,
    MPI_Comm comm,
    const foamDistributionMesh& distMesh,
    const bool thermal,
    const fileName& restartFile,
    const double restartTime
)
{
    // the case folder (not processorN/): LAMMPS reads one input for all ranks
    const fileName input(mesh.time().globalPath()/requiredWord(dict, "lammpsInput"));
    const fileName log
    (
        mesh.time().globalPath()/dict.getOrDefault<word>("lammpsLog", "log.lammps")
    );
    Info<< "Particles: LAMMPS input " << input << ", log " << log << endl;

    // LAMMPS opens its input's files (include, read_data, dump, fix print) relative to the
    // working folder: make it the case's, as for a run started in the case (-case DIR elsewhere)
    if (cwd(false) != mesh.time().globalPath())
    {
        Info<< "Particles: working folder " << cwd(false) << " -> " << mesh.time().globalPath()
            << " (the LAMMPS input's file names are the case's)" << endl;
        if (!chDir(mesh.time().globalPath()))
        {
            FatalErrorInFunction
                << "cannot change the working folder to the case " << mesh.time().globalPath()
                << exit(FatalError);
        }
    }
    try
    {
        lammps_.reset
        (
            new ::meltdem::LammpsCouplingHost
            (
                comm, input, log, false, restartFile, restartTime
            )
        );
    }
    catch (const ::meltdem::LammpsSetupError& e)
    {
        FatalIOErrorInFunction(dict)
            << "lammpsInput: " << e.what() << exit(FatalIOError);
    }
    if (!lammps_->resume_limitation().empty())
    {
        WarningInFunction
            << "this run can not be resumed from its checkpoints: "
            << lammps_->resume_limitation() << endl;
    }
    checkMaterial(*lammps_, meltdemDict, thermal);
    checkDomains(*lammps_, distMesh, dict, comm);
    checkGravity(mesh, *lammps_, dict);
}
