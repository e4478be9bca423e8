#include "particlesRefinement.H"
#include "laserHeatSource.H"
#include "addToRunTimeSelectionTable.H"
#include "cellBoxTree.H"

namespace Foam
{
namespace meltdem
{

defineTypeNameAndDebug(particlesRefinement, 0);
addToRunTimeSelectionTable(refinementCriterion, particlesRefinement, dictionary);


particlesRefinement::particlesRefinement
(
    const word& name, const dictionary& dict, const fvMesh& mesh, const label maxLevel
)
:
    refinementCriterion(name, dict, mesh, maxLevel),
    diameters_(nonNegative("diameters", 1)),
    nearPool_(false),
    nearBeam_(false),
    anywhere_(false)
{
    const IOdictionary& props = mesh.lookupObject<IOdictionary>("meltdemProperties");
    const dictionary& physics = props.subDict("physics");
    if (!physics.getOrDefault<bool>("particles", false))
    {
        FatalIOErrorInFunction(dict)
            << "refinement criterion '" << name << "' (particles) needs physics { particles on; }"
            << exit(FatalIOError);
    }
    const wordList near(dict.getOrDefault<wordList>("near", wordList{"pool", "beam"}));
    if (near.empty())
    {
        FatalIOErrorInFunction(dict)
            << "refinement criterion '" << name << "': near is empty (give pool, beam or anywhere)"
            << exit(FatalIOError);
    }
    for (const word& w : near)
    {
        if (w == "pool") nearPool_ = true;
        else if (w == "beam") nearBeam_ = true;
        else if (w == "anywhere") anywhere_ = true;
        else
        {
            FatalIOErrorInFunction(dict)
                << "refinement criterion '" << name << "': near '" << w
                << "' is not pool, beam or anywhere" << exit(FatalIOError);
        }
    }
    if (nearPool_ && !physics.getOrDefault<bool>("energy", false))
    {
        FatalIOErrorInFunction(dict)
            << "refinement criterion '" << name << "': near pool needs physics { energy on; }"
            << exit(FatalIOError);
    }
}


void particlesRefinement::mark(const state& s, bitSet& cells) const
{
    if (s.particleCentres.empty()) return;
    const scalarField& a = mesh_.lookupObject<volScalarField>(s.alphaName).primitiveField();
    const scalarField* fl =
        nearPool_ ? &mesh_.lookupObject<volScalarField>("liquidFraction").primitiveField() : nullptr;
    const indexedOctree<treeDataCell>& tree = cellBoxTree::New(mesh_).tree();

    // whether each grain is near the pool on this rank, then on any rank
    const label n = s.particleCentres.size();
    List<labelList> reach(n);
    boolList near(n, anywhere_);
    forAll(s.particleCentres, i)
    {
        const point& c = s.particleCentres[i];
        const scalar r = s.particleRadii[i]*(1 + 2*diameters_);
        reach[i] = tree.findBox(treeBoundBox(c - point::uniform(r), c + point::uniform(r)));
        if (fl && !near[i])
        {
            for (const label celli : reach[i])
            {
                if (a[celli] > 0.5 && (*fl)[celli] > 0) { near[i] = true; break; }
            }
        }
        if (nearBeam_ && !near[i] && s.laser && s.laser->on())
        {
            const vector d = s.laser->direction()/mag(s.laser->direction());
            const vector rel = c - s.laser->position();
            near[i] = mag(rel - (rel & d)*d) <= s.laser->radius() + r;
        }
    }
    Pstream::listCombineGather(near, orEqOp<bool>());
    Pstream::listCombineScatter(near);
    forAll(near, i)
    {
        if (!near[i]) continue;
        for (const label celli : reach[i]) cells.set(celli);
    }
}

} // End namespace meltdem
} // End namespace Foam
