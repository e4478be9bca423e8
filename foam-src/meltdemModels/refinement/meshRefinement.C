#include "meshRefinement.H"
#include "meltdemProperties.H"
#include "meltdemRefineFvMesh.H"
#include "cellContentRemap.H"
#include "IOdictionary.H"
#include "IFstream.H"
#include "OSspecific.H"
#include "syncTools.H"
#include "wedgePolyPatch.H"
#include "emptyPolyPatch.H"

#include <cmath>
#include <limits>

namespace Foam
{
namespace meltdem
{

const word meshRefinement::dictName("refinement");
const word meshRefinement::requestName("meltdemRefinementRequest");

namespace
{

const char* const generatedMarker =
    "// written by meltdemFoam from constant/meltdemProperties refinement{}: edit that instead";

label readLabel
(
    const dictionary& d, const word& key, const label deflt, const label lowest, const bool required
)
{
    if (required && !d.found(key))
    {
        FatalIOErrorInFunction(d)
            << "missing entry '" << key << "' in " << d.name() << exit(FatalIOError);
    }
    const label v = d.getOrDefault<label>(key, deflt);
    if (v < lowest)
    {
        FatalIOErrorInFunction(d)
            << "entry '" << key << "' = " << v << " in " << d.name() << " must be at least "
            << lowest << exit(FatalIOError);
    }
    return v;
}

void checkKeys(const dictionary& d)
{
    meltdemProperties::checkEntries(d, {"maxLevel", "refineInterval", "nBufferLayers", "maxCells", "criteria"});
    if (!d.isDict("criteria") || d.subDict("criteria").empty())
    {
        FatalIOErrorInFunction(d)
            << "refinement needs a non-empty sub-dictionary 'criteria' in " << d.name()
            << " (interface, meltPool, laser, field)" << exit(FatalIOError);
    }
}

} // End anonymous namespace


bool meshRefinement::writeMeshDict(const Time& runTime)
{
    const IOdictionary props
    (
        IOobject
        (
            "meltdemProperties", runTime.constant(), runTime,
            IOobject::MUST_READ, IOobject::NO_WRITE, false
        )
    );
    const fileName caseDir(runTime.rootPath()/runTime.globalCaseName());
    const fileName meshDict(caseDir/"constant"/"dynamicMeshDict");
    bool generated = false;
    if (isFile(meshDict))
    {
        IFstream is(meshDict);
        string line;
        is.getLine(line);
        generated = (line == generatedMarker);
    }
    const bool refining = props.found(dictName);
    if (!refining)
    {
        if (generated && Pstream::master()) rm(meshDict);
        label sync = 0;
        reduce(sync, sumOp<label>());
        return false;
    }
    if (!props.isDict(dictName))
    {
        FatalIOErrorInFunction(props)
            << "'" << dictName << "' must be a sub-dictionary" << exit(FatalIOError);
    }
    const dictionary& d = props.subDict(dictName);
    checkKeys(d);
    if (isFile(meshDict) && !generated)
    {
        FatalIOErrorInFunction(d)
            << "both " << meshDict << " and constant/meltdemProperties refinement{} give the"
               " mesh's refinement: remove dynamicMeshDict (meltdemFoam writes it from"
               " refinement{})" << exit(FatalIOError);
    }
    const label maxLevel = readLabel(d, "maxLevel", 0, 1, true);
    const label interval = readLabel(d, "refineInterval", 1, 1, false);
    const label maxCells = readLabel(d, "maxCells", 100000000, 1, false);

    const IOdictionary transport
    (
        IOobject
        (
            "transportProperties", runTime.constant(), runTime,
            IOobject::MUST_READ, IOobject::NO_WRITE, false
        )
    );
    const word metal(transport.get<wordList>("phases")[0]);

    if (Pstream::master())
    {
        OFstream os(meshDict);
        os  << generatedMarker << nl
            << "FoamFile { version 2.0; format ascii; class dictionary;"
               " location \"constant\"; object dynamicMeshDict; }" << nl << nl
            << "dynamicFvMesh   " << meltdemRefineFvMesh::typeName << ";" << nl << nl
            << dynamicRefineFvMesh::typeName << "Coeffs" << nl
            << "{" << nl
            << "    refineInterval   " << interval << ";" << nl
            << "    field            " << requestName << ";" << nl
            << "    lowerRefineLevel 0.5;" << nl
            << "    upperRefineLevel 1e30;" << nl
            << "    unrefineLevel    -0.5;" << nl
            << "    nBufferLayers    1;" << nl
            << "    maxRefinement    " << maxLevel << ";" << nl
            << "    maxCells         " << maxCells << ";" << nl
            << "    dumpLevel        false;" << nl
            << "    // fluxes recomputed each step (phi by correctPhi)" << nl
            << "    correctFluxes" << nl
            << "    (" << nl
            << "        (phi none) (nHatf none) (rhoPhi none) (ghf none) (TBlendingFactor none)" << nl
            << "        (alphaPhi0." << metal << " none) (alphaPhiMetal none) (alphaPhiUn none)" << nl
            << "    );" << nl
            << "}" << nl;
    }
    label sync = 0;
    reduce(sync, sumOp<label>());
    return true;
}


meshRefinement::meshRefinement(dynamicFvMesh& mesh, const dictionary& properties)
:
    mesh_(mesh),
    dict_(properties.subDict(dictName)),
    maxLevel_(readLabel(dict_, "maxLevel", 0, 1, true)),
    refineInterval_(readLabel(dict_, "refineInterval", 1, 1, false)),
    nBufferLayers_(readLabel(dict_, "nBufferLayers", 1, 0, false)),
    criteria_(),
    request_
    (
        IOobject(requestName, mesh.time().timeName(), mesh, IOobject::NO_READ, IOobject::NO_WRITE),
        mesh,
        dimensionedScalar("zero", dimless, 0)
    ),
    nBefore_(0),
    nAfter_(0)
{
    checkMesh();
    const dictionary& cd = dict_.subDict("criteria");
    for (const word& name : cd.toc())
    {
        if (!cd.isDict(name))
        {
            FatalIOErrorInFunction(cd)
                << "refinement criterion '" << name << "' must be a sub-dictionary"
                << exit(FatalIOError);
        }
        criteria_.append(refinementCriterion::New(name, cd.subDict(name), mesh, maxLevel_));
    }
    Info<< "Refinement: up to level " << maxLevel_ << " every " << refineInterval_
        << " steps, criteria " << cd.toc() << endl;
}


void meshRefinement::checkMesh() const
{
    if (!isA<meltdemRefineFvMesh>(mesh_))
    {
        FatalIOErrorInFunction(dict_)
            << "refinement{} needs the mesh type meltdemFoam writes into"
               " constant/dynamicMeshDict; this mesh is " << mesh_.type() << exit(FatalIOError);
    }
    for (const polyPatch& pp : mesh_.boundaryMesh())
    {
        if (isA<emptyPolyPatch>(pp) || isA<wedgePolyPatch>(pp))
        {
            FatalIOErrorInFunction(dict_)
                << "refinement needs a 3D mesh of hexahedra: patch '" << pp.name() << "' is "
                << pp.type() << " (a 2D or axisymmetric mesh cannot be split in eight)"
                << exit(FatalIOError);
        }
    }
    const auto& refiner = refCast<const dynamicRefineFvMesh>(mesh_);
    const label nProtected = returnReduce(label(refiner.protectedCell().count()), sumOp<label>());
    if (nProtected > 0)
    {
        FatalIOErrorInFunction(dict_)
            << "refinement needs a mesh of hexahedra: " << nProtected
            << " cells cannot be split in eight (not hexahedra)" << exit(FatalIOError);
    }
    const labelList& cellLevel = refiner.meshCutter().cellLevel();
    const label levelNow = returnReduce(cellLevel.empty() ? label(0) : max(cellLevel), maxOp<label>());
    if (levelNow > maxLevel_)
    {
        FatalIOErrorInFunction(dict_)
            << "maxLevel " << maxLevel_ << " is below the level " << levelNow
            << " the mesh already has" << exit(FatalIOError);
    }
    const double nMax =
        double(mesh_.globalData().nTotalCells())*std::pow(8.0, double(maxLevel_ - levelNow));
    if (nMax > double(std::numeric_limits<label>::max()))
    {
        FatalIOErrorInFunction(dict_)
            << "maxLevel " << maxLevel_ << ": the mesh's " << mesh_.globalData().nTotalCells()
            << " cells could become " << nMax << ", beyond this OpenFOAM's label range ("
            << std::numeric_limits<label>::max() << ")" << exit(FatalIOError);
    }
}


bool meshRefinement::needsParticles() const
{
    for (const refinementCriterion& c : criteria_)
    {
        if (c.type() == "particles") return true;
    }
    return false;
}


void meshRefinement::idle()
{
    mesh_.topoChanging(false);
}


bool meshRefinement::due() const
{
    const label index = mesh_.time().timeIndex();
    return index > 0 && index % refineInterval_ == 0;
}


labelList meshRefinement::requestedLevel(const refinementCriterion::state& s) const
{
    labelList level(mesh_.nCells(), 0);
    bitSet marked(mesh_.nCells());
    for (const refinementCriterion& c : criteria_)
    {
        marked.reset();
        c.mark(s, marked);
        for (const label celli : marked)
        {
            level[celli] = max(level[celli], c.level());
        }
    }
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    for (label layer = 0; layer < nBufferLayers_; ++layer)
    {
        labelList wider(level);
        forAll(nei, facei)
        {
            wider[own[facei]] = max(wider[own[facei]], level[nei[facei]]);
            wider[nei[facei]] = max(wider[nei[facei]], level[own[facei]]);
        }
        labelList across;
        syncTools::swapBoundaryCellList(mesh_, level, across);
        const label start = mesh_.nInternalFaces();
        forAll(across, bFacei)
        {
            const label facei = start + bFacei;
            if (mesh_.boundaryMesh()[mesh_.boundaryMesh().whichPatch(facei)].coupled())
            {
                wider[own[facei]] = max(wider[own[facei]], across[bFacei]);
            }
        }
        level.transfer(wider);
    }
    equalLevelsAcrossInterface(s, level);
    return level;
}


void meshRefinement::equalLevelsAcrossInterface
(
    const refinementCriterion::state& s, labelList& level
) const
{
    // the curvature of a flat interface is zero only where the cells on its two sides are
    // alike: a level jump across it gives a spurious curvature and parasitic currents
    const volScalarField* alphaPtr = mesh_.findObject<volScalarField>(s.alphaName);
    if (!alphaPtr) return;
    const scalarField& a = alphaPtr->primitiveField();
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const label start = mesh_.nInternalFaces();
    auto crossed = [](const scalar aP, const scalar aN) { return (aP < 0.5) != (aN < 0.5); };
    scalarField aAcross;
    syncTools::swapBoundaryCellList(mesh_, a, aAcross);
    for (label pass = 0; pass < 100; ++pass)
    {
        label raised = 0;
        forAll(nei, facei)
        {
            label& lP = level[own[facei]];
            label& lN = level[nei[facei]];
            if (lP != lN && crossed(a[own[facei]], a[nei[facei]]))
            {
                ++raised;
                lP = lN = max(lP, lN);
            }
        }
        labelList across;
        syncTools::swapBoundaryCellList(mesh_, level, across);
        forAll(across, bFacei)
        {
            const label facei = start + bFacei;
            label& lP = level[own[facei]];
            if
            (
                mesh_.boundaryMesh()[mesh_.boundaryMesh().whichPatch(facei)].coupled()
             && across[bFacei] > lP && crossed(a[own[facei]], aAcross[bFacei])
            )
            {
                ++raised;
                lP = across[bFacei];
            }
        }
        if (returnReduce(raised, sumOp<label>()) == 0) break;
    }
}


bool meshRefinement::update
(
    const refinementCriterion::state& s,
    HashTable<scalarField>& contents,
    const HashTable<scalarField>& ranges
)
{
    const auto& refiner = refCast<const dynamicRefineFvMesh>(mesh_);
    const labelList level(requestedLevel(s));
    const labelList& cellLevel = refiner.meshCutter().cellLevel();
    scalarField& request = request_.primitiveFieldRef();
    forAll(request, celli)
    {
        request[celli] = level[celli] - cellLevel[celli];
    }
    request_.correctBoundaryConditions();

    cellContentRemap& remap = const_cast<cellContentRemap&>(cellContentRemap::New(mesh_));
    contentNames_ = contents.sortedToc();
    before_.setSize(contentNames_.size());
    forAll(contentNames_, i)
    {
        remap.hold(contentNames_[i], contents[contentNames_[i]]);
        before_[i] = gSum(contents[contentNames_[i]]*mesh_.V().field());
    }
    forAllConstIters(ranges, iter)
    {
        remap.holdRange(iter.key(), iter.val());
    }
    nBefore_ = mesh_.globalData().nTotalCells();

    mesh_.update();

    after_.setSize(contentNames_.size());
    lost_.setSize(contentNames_.size());
    forAll(contentNames_, i)
    {
        contents.set(contentNames_[i], scalarField(remap.release(contentNames_[i])));
        after_[i] = gSum(contents[contentNames_[i]]*mesh_.V().field());
        lost_[i] = returnReduce(remap.lost(contentNames_[i]), sumOp<scalar>());
    }
    lowest_.clear();
    highest_.clear();
    forAllConstIters(ranges, iter)
    {
        scalarField lo, hi;
        remap.releaseRange(iter.key(), lo, hi);
        lowest_.set(iter.key(), lo);
        highest_.set(iter.key(), hi);
    }
    nAfter_ = mesh_.globalData().nTotalCells();
    return mesh_.topoChanging();
}


void meshRefinement::book(const HashTable<const scalarField*>& values)
{
    const auto& refiner = refCast<const dynamicRefineFvMesh>(mesh_);
    const label levelMax = returnReduce(max(refiner.meshCutter().cellLevel()), maxOp<label>());
    const wordList ranged(lowest_.sortedToc());
    labelList outside(ranged.size(), 0);
    forAll(ranged, i)
    {
        const scalarField& v = *values[ranged[i]];
        const scalarField& lo = lowest_[ranged[i]];
        const scalarField& hi = highest_[ranged[i]];
        forAll(v, celli)
        {
            const scalar tol = 1e-10*max(mag(lo[celli]), mag(hi[celli]));
            if (v[celli] < lo[celli] - tol || v[celli] > hi[celli] + tol) ++outside[i];
        }
        reduce(outside[i], sumOp<label>());
    }

    Info<< "Refinement: " << nBefore_ << " -> " << nAfter_ << " cells, finest level " << levelMax;
    forAll(contentNames_, i)
    {
        Info<< ", " << contentNames_[i] << " change " << after_[i] - before_[i];
    }
    forAll(ranged, i)
    {
        Info<< ", " << ranged[i] << " outside its cells' range in " << outside[i] << " cells";
    }
    Info<< endl;

    if (!Pstream::master()) return;
    wordList header{"time", "cellsBefore", "cellsAfter", "finestLevel"};
    for (const word& n : contentNames_)
    {
        for (const char* what : {"Before", "After", "Error", "Lost"})
        {
            header.append(n + what);
        }
    }
    for (const word& n : ranged)
    {
        header.append(n + "OutsideRange");
    }
    if (!csv_.valid() || csvHeader_ != header)
    {
        const Time& time = mesh_.time();
        const fileName dir
        (
            time.globalPath()/"postProcessing"/"refinement"/time.timeName(time.startTime().value())
        );
        mkDir(dir);
        csv_.reset(new OFstream(dir/"refinement.csv"));
        csv_().precision(17);
        csvHeader_ = header;
        forAll(header, i)
        {
            csv_() << (i ? "," : "") << header[i];
        }
        csv_() << nl;
    }
    csv_() << mesh_.time().value() << ',' << nBefore_ << ',' << nAfter_ << ',' << levelMax;
    forAll(contentNames_, i)
    {
        csv_() << ',' << before_[i] << ',' << after_[i] << ',' << after_[i] - before_[i] << ','
               << lost_[i];
    }
    for (const label n : outside)
    {
        csv_() << ',' << n;
    }
    csv_() << endl;
}

} // End namespace meltdem
} // End namespace Foam
