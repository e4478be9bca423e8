#include "laserRefinement.H"
#include "laserHeatSource.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
namespace meltdem
{

defineTypeNameAndDebug(laserRefinement, 0);
addToRunTimeSelectionTable(refinementCriterion, laserRefinement, dictionary);


laserRefinement::laserRefinement
(
    const word& name, const dictionary& dict, const fvMesh& mesh, const label maxLevel
)
:
    refinementCriterion(name, dict, mesh, maxLevel),
    radii_(nonNegative("radii", 1.5)),
    depth_(dict.found("depth") ? nonNegative("depth", 0) : -1),
    lookAhead_(dict.getOrDefault<label>("lookAhead", 0)),
    lookAheadTime_(nonNegative("lookAheadTime", 0))
{
    const IOdictionary& props = mesh.lookupObject<IOdictionary>("meltdemProperties");
    if (!props.subDict("physics").getOrDefault<bool>("laser", false))
    {
        FatalIOErrorInFunction(dict)
            << "refinement criterion '" << name << "' (laser) needs physics { laser on; }"
            << exit(FatalIOError);
    }
    if (!(radii_ > 0))
    {
        FatalIOErrorInFunction(dict)
            << "refinement criterion '" << name << "': radii " << radii_
            << " must be positive (the footprint's reach in beam radii)" << exit(FatalIOError);
    }
    if (lookAhead_ < 0)
    {
        FatalIOErrorInFunction(dict)
            << "refinement criterion '" << name << "': lookAhead " << lookAhead_
            << " must be a non-negative number of steps" << exit(FatalIOError);
    }
}


void laserRefinement::mark(const state& s, bitSet& cells) const
{
    if (!s.laser) return;
    const laserHeatSource& beam = *s.laser;
    const scalarField& a = mesh_.lookupObject<volScalarField>(s.alphaName).primitiveField();
    const vectorField& C = mesh_.C().primitiveField();
    const vector d = beam.direction()/mag(beam.direction());
    const scalar R = radii_*beam.radius();
    const scalar depth = depth_ < 0 ? R : depth_;

    // positions now and along the path ahead, no further apart than half a beam radius
    const scalar t0 = mesh_.time().value();
    const scalar ahead = max(lookAhead_*s.deltaT, lookAheadTime_);
    const scalar travel = mag(beam.position(t0 + ahead) - beam.position(t0));
    const label nSamples = 1 + (ahead > 0 ? label(ceil(2*travel/max(beam.radius(), VSMALL))) + 1 : 0);
    for (label k = 0; k < nSamples; ++k)
    {
        const scalar t = nSamples > 1 ? t0 + ahead*k/(nSamples - 1) : t0;
        if (!beam.on(t) && !(k == 0 && beam.on())) continue;
        const point p = beam.position(t);
        // the first metal along the beam inside the footprint
        scalar surface = GREAT;
        forAll(C, celli)
        {
            const vector r = C[celli] - p;
            const scalar along = r & d;
            if (a[celli] > 0.5 && magSqr(r - along*d) <= R*R) surface = min(surface, along);
        }
        reduce(surface, minOp<scalar>());
        if (surface == GREAT) continue;
        forAll(C, celli)
        {
            const vector r = C[celli] - p;
            const scalar along = r & d;
            if
            (
                along >= surface - R && along <= surface + depth
             && magSqr(r - along*d) <= R*R
            )
            {
                cells.set(celli);
            }
        }
    }
}

} // End namespace meltdem
} // End namespace Foam
