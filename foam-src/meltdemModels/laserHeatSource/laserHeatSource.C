/*---------------------------------------------------------------------------*\
    MeltDEM: moving Gaussian laser heat source (see laserHeatSource.H).
\*---------------------------------------------------------------------------*/

#include "laserHeatSource.H"
#include "meltdemProperties.H"
#include "fvc.H"
#include "mathematicalConstants.H"

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::meltdem::laserHeatSource::laserHeatSource
(
    const fvMesh& mesh,
    const dictionary& dict
)
:
    mesh_(mesh),
    power_(dict.get<scalar>("power")),
    absorptivity_(dict.get<scalar>("absorptivity")),
    linearAbsorptivity_(false),
    absorptivity0_(absorptivity_),
    dAbsorptivitydT_(0),
    Tabsorptivity_(0),
    absorptivityMin_(dict.getOrDefault<scalar>("absorptivityMin", 0)),
    absorptivityMax_(dict.getOrDefault<scalar>("absorptivityMax", 1)),
    radius_(dict.get<scalar>("radius")),
    direction_(dict.getOrDefault<vector>("direction", vector(0, 0, -1))),
    tOn_(dict.getOrDefault<scalar>("tOn", 0)),
    tOff_(dict.getOrDefault<scalar>("tOff", GREAT)),
    minHitFraction_(dict.getOrDefault<scalar>("minHitFraction", 1e-3)),
    alphaWeighted_(true),
    timeAveraged_(dict.getOrDefault<bool>("timeAveraged", true)),
    scaleByHitFraction_(dict.getOrDefault<bool>("scaleByHitFraction", false)),
    points_(),
    arcLength_(),
    polyline_(dict.found("path")),
    tracks_(dict.found("tracks")),
    knotTimes_(),
    knotPoints_(),
    onIntervals_(1, Pair<scalar>(tOn_, tOff_)),
    velocity_(Zero),
    speed_(0),
    tStart_(dict.getOrDefault<scalar>("tStart", 0)),
    tStop_(dict.getOrDefault<scalar>("tStop", GREAT)),
    transmittedShare_(1),
    absorbedPower_(0),
    hitFraction_(0)
{
    if (power_ < 0)
    {
        FatalIOErrorInFunction(dict)
            << "power (" << power_ << ") must be >= 0 [W] in " << dict.name()
            << exit(FatalIOError);
    }
    if (absorptivity_ < 0 || absorptivity_ > 1)
    {
        FatalIOErrorInFunction(dict)
            << "absorptivity (" << absorptivity_ << ") must be in [0,1] in "
            << dict.name() << exit(FatalIOError);
    }
    const word model(dict.getOrDefault<word>("absorptivityModel", "constant"));
    if (model == "linear")
    {
        linearAbsorptivity_ = true;
        dAbsorptivitydT_ = dict.get<scalar>("dAbsorptivitydT");
        Tabsorptivity_ = dict.get<scalar>("Tabsorptivity");
        if (!(Tabsorptivity_ > 0))
        {
            FatalIOErrorInFunction(dict)
                << "Tabsorptivity (" << Tabsorptivity_ << ") must be an absolute"
                << " temperature > 0 [K] in " << dict.name() << exit(FatalIOError);
        }
        if
        (
            !(absorptivityMin_ >= 0 && absorptivityMin_ <= absorptivityMax_
           && absorptivityMax_ <= 1)
        )
        {
            FatalIOErrorInFunction(dict)
                << "absorptivityMin (" << absorptivityMin_ << ") and absorptivityMax ("
                << absorptivityMax_ << ") must satisfy 0 <= min <= max <= 1 in "
                << dict.name() << exit(FatalIOError);
        }
    }
    else if (model != "constant")
    {
        FatalIOErrorInFunction(dict)
            << "absorptivityModel '" << model << "' is not one of (constant linear) in "
            << dict.name() << exit(FatalIOError);
    }
    if (!(radius_ > 0))
    {
        FatalIOErrorInFunction(dict)
            << "radius (" << radius_ << ") must be > 0 [m] (1/e^2 radius) in "
            << dict.name() << exit(FatalIOError);
    }
    if (mag(direction_) < VSMALL)
    {
        FatalIOErrorInFunction(dict)
            << "direction " << direction_ << " must be non-zero in "
            << dict.name() << exit(FatalIOError);
    }
    direction_ /= mag(direction_);
    if (tOff_ < tOn_)
    {
        FatalIOErrorInFunction(dict)
            << "tOff (" << tOff_ << ") must be >= tOn (" << tOn_ << ") in "
            << dict.name() << exit(FatalIOError);
    }
    if (tStop_ < tStart_)
    {
        FatalIOErrorInFunction(dict)
            << "tStop (" << tStop_ << ") must be >= tStart (" << tStart_
            << ") in " << dict.name() << exit(FatalIOError);
    }
    if (minHitFraction_ < 0 || minHitFraction_ >= 1)
    {
        FatalIOErrorInFunction(dict)
            << "minHitFraction (" << minHitFraction_ << ") must be in [0,1) in "
            << dict.name() << exit(FatalIOError);
    }

    const word distribution
    (
        dict.getOrDefault<word>("distribution", "alphaWeighted")
    );
    if (distribution == "gradAlpha")
    {
        alphaWeighted_ = false;
    }
    else if (distribution != "alphaWeighted")
    {
        FatalIOErrorInFunction(dict)
            << "distribution " << distribution << " unknown (alphaWeighted or "
            << "gradAlpha) in " << dict.name() << exit(FatalIOError);
    }

    // the end of the motion: the path must stay in the mesh until then
    const scalar tEnd = min(tStop_, tOff_);

    if (tracks_)
    {
        readTracks(dict);
    }
    else if (polyline_)
    {
        if (dict.found("position") || dict.found("velocity"))
        {
            FatalIOErrorInFunction(dict)
                << "path: give either path (with speed) or position (with "
                << "velocity), not both, in " << dict.name() << exit(FatalIOError);
        }
        points_ = dict.get<pointField>("path");
        speed_ = dict.get<scalar>("speed");
        if (points_.empty())
        {
            FatalIOErrorInFunction(dict)
                << "path must have at least one point in " << dict.name()
                << exit(FatalIOError);
        }
        if (speed_ < 0)
        {
            FatalIOErrorInFunction(dict)
                << "speed (" << speed_ << ") must be >= 0 [m/s] in "
                << dict.name() << exit(FatalIOError);
        }
        arcLength_.setSize(points_.size());
        arcLength_[0] = 0;
        for (label i = 1; i < points_.size(); ++i)
        {
            arcLength_[i] = arcLength_[i-1] + mag(points_[i] - points_[i-1]);
        }
        forAll(points_, i)
        {
            checkInBounds(dict, "path", points_[i]);
        }
    }
    else
    {
        points_.setSize(1);
        points_[0] = dict.get<point>("position");
        velocity_ = dict.getOrDefault<vector>("velocity", Zero);
        checkInBounds(dict, "position", points_[0]);
        if (mag(velocity_) > 0)
        {
            if (tEnd >= 0.5*GREAT)
            {
                FatalIOErrorInFunction(dict)
                    << "velocity " << velocity_ << " is non-zero but neither tStop "
                    << "nor tOff is given: the path would leave the mesh, in "
                    << dict.name() << exit(FatalIOError);
            }
            checkInBounds(dict, "velocity", position(tEnd));
        }
    }

    // every entry must be one the beam's path mode and absorptivity model read: a misspelt
    // velocity would leave the beam standing, a misspelt tOff leave it on
    wordList known
    {
        "power", "absorptivity", "absorptivityModel", "radius", "direction", "tOn", "tOff",
        "tStart", "tStop", "minHitFraction", "timeAveraged", "scaleByHitFraction", "distribution"
    };
    const auto add = [&known](std::initializer_list<const char*> keys)
    {
        for (const char* k : keys) known.append(word(k));
    };
    if (linearAbsorptivity_) add({"dAbsorptivitydT", "Tabsorptivity", "absorptivityMin", "absorptivityMax"});
    if (tracks_) add({"tracks", "speed", "returnTime"});
    else if (polyline_) add({"path", "speed"});
    else add({"position", "velocity"});
    meltdemProperties::checkEntries
    (
        dict, known,
        string(tracks_ ? "tracks" : polyline_ ? "path" : "position") + " mode, absorptivityModel "
      + (linearAbsorptivity_ ? "linear" : "constant")
    );

    Info<< "laserHeatSource: " << (alphaWeighted_ ? "alphaWeighted" : "gradAlpha")
        << " distribution, P = " << power_ << " W, eta = " << absorptivity_
        << ", 1/e^2 radius = " << radius_ << " m, direction " << direction_
        << ", on in [" << tOn_ << ", " << tOff_ << ")"
        << (tracks_ ? ", " + Foam::name(knotTimes_.size()/2) + " tracks"
            : polyline_ ? word(", polyline path") : word(", linear path"))
        << endl;
}


// * * * * * * * * * * * * * * * Private Functions * * * * * * * * * * * * * //

void Foam::meltdem::laserHeatSource::checkInBounds
(
    const dictionary& dict,
    const word& entry,
    const point& p
) const
{
    // polyMesh::bounds() is the global box (reduced over processors)
    const boundBox& bb = mesh_.bounds();
    const scalar tol = 1e-9*mag(bb.span());
    const boundBox grown(bb.min() - vector::one*tol, bb.max() + vector::one*tol);
    if (!grown.contains(p))
    {
        FatalIOErrorInFunction(dict)
            << entry << ": laser path point " << p << " lies outside the mesh "
            << "bounds " << bb << " in " << dict.name() << exit(FatalIOError);
    }
}


void Foam::meltdem::laserHeatSource::readTracks(const dictionary& dict)
{
    for (const word& other : {"path", "position", "velocity", "tStop"})
    {
        if (dict.found(other))
        {
            FatalIOErrorInFunction(dict)
                << "tracks: " << other << " cannot be combined with tracks in "
                << dict.name() << exit(FatalIOError);
        }
    }
    const List<Pair<point>> tracks(dict.get<List<Pair<point>>>("tracks"));
    speed_ = dict.get<scalar>("speed");
    const scalar returnTime = dict.get<scalar>("returnTime");
    if (tracks.empty())
    {
        FatalIOErrorInFunction(dict)
            << "tracks must have at least one track in " << dict.name()
            << exit(FatalIOError);
    }
    if (!(speed_ > 0))
    {
        FatalIOErrorInFunction(dict)
            << "speed (" << speed_ << ") must be > 0 [m/s] with tracks in "
            << dict.name() << exit(FatalIOError);
    }
    if (returnTime < 0)
    {
        FatalIOErrorInFunction(dict)
            << "returnTime (" << returnTime << ") must be >= 0 [s] in "
            << dict.name() << exit(FatalIOError);
    }
    knotTimes_.setSize(2*tracks.size());
    knotPoints_.setSize(2*tracks.size());
    onIntervals_.clear();
    scalar t = tStart_;
    forAll(tracks, i)
    {
        checkInBounds(dict, "tracks", tracks[i].first());
        checkInBounds(dict, "tracks", tracks[i].second());
        const scalar duration = mag(tracks[i].second() - tracks[i].first())/speed_;
        knotTimes_[2*i] = t;
        knotPoints_[2*i] = tracks[i].first();
        knotTimes_[2*i + 1] = t + duration;
        knotPoints_[2*i + 1] = tracks[i].second();
        // the track's scan, within [tOn, tOff)
        const scalar begin = max(t, tOn_);
        const scalar end = min(t + duration, tOff_);
        if (end > begin)
        {
            onIntervals_.append(Pair<scalar>(begin, end));
        }
        t += duration + returnTime;
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

bool Foam::meltdem::laserHeatSource::on(const scalar t) const
{
    for (const Pair<scalar>& interval : onIntervals_)
    {
        if (t >= interval.first() && t < interval.second())
        {
            return true;
        }
    }
    return false;
}


Foam::vector Foam::meltdem::laserHeatSource::position(const scalar t) const
{
    if (tracks_)
    {
        if (t <= knotTimes_.first())
        {
            return knotPoints_.first();
        }
        for (label i = 1; i < knotTimes_.size(); ++i)
        {
            if (t <= knotTimes_[i])
            {
                const scalar span = knotTimes_[i] - knotTimes_[i-1];
                const scalar w = span > 0 ? (t - knotTimes_[i-1])/span : 1;
                return knotPoints_[i-1] + w*(knotPoints_[i] - knotPoints_[i-1]);
            }
        }
        return knotPoints_.last();
    }
    const scalar tau = max(min(t, tStop_) - tStart_, scalar(0));
    if (!polyline_)
    {
        return points_[0] + velocity_*tau;
    }
    const scalar s = speed_*tau;
    for (label i = 1; i < points_.size(); ++i)
    {
        if (s <= arcLength_[i])
        {
            const scalar len = arcLength_[i] - arcLength_[i-1];
            const scalar w = len > 0 ? (s - arcLength_[i-1])/len : 0;
            return points_[i-1] + w*(points_[i] - points_[i-1]);
        }
    }
    return points_.last();
}


Foam::scalar Foam::meltdem::laserHeatSource::onFraction() const
{
    const scalar t = mesh_.time().value();
    const scalar dt = mesh_.time().deltaTValue();
    if (!timeAveraged_ || !(dt > 0))
    {
        return on(t) ? 1 : 0;
    }
    scalar lit = 0;
    for (const Pair<scalar>& interval : onIntervals_)
    {
        lit += max(min(t, interval.second()) - max(t - dt, interval.first()), scalar(0));
    }
    return lit/dt;
}


Foam::tmp<Foam::volScalarField> Foam::meltdem::laserHeatSource::heatSource
(
    const volScalarField& alphaMetal
) const
{
    tmp<volScalarField> tq
    (
        new volScalarField
        (
            IOobject
            (
                "laserHeatSourceModel",
                mesh_.time().timeName(),
                mesh_,
                IOobject::NO_READ,
                IOobject::NO_WRITE,
                false
            ),
            mesh_,
            dimensionedScalar("zero", dimPower/dimVolume, 0)
        )
    );
    volScalarField& q = tq.ref();
    absorbedPower_ = 0;
    hitFraction_ = 0;

    const scalar t = mesh_.time().value();
    const scalar lit = min(onFraction(), scalar(1));
    if (lit <= 0 || power_*absorptivity_ <= 0)
    {
        return tq;
    }

    const vectorField& C = mesh_.C();
    scalarField& qi = q.primitiveFieldRef();
    qi = facingShape(alphaMetal, position(t));
    const scalar raw = gSum(qi*mesh_.V());
    if (shadow_)
    {
        // what the particles above a cell leave of the beam there
        forAll(qi, celli)
        {
            if (qi[celli] > 0)
            {
                qi[celli] *= shadow_(C[celli], 0.5*Foam::cbrt(mesh_.V()[celli]));
            }
        }
    }
    if (alphaWeighted_)
    {
        qi *= max(min(alphaMetal.primitiveField(), scalar(1)), scalar(0));
    }

    // the normalisation is that of the weighted (and shadowed) shape; the hit test uses
    // the plain one
    const scalar weighted = gSum(qi*mesh_.V());
    hitFraction_ = 2*raw/(constant::mathematical::pi*sqr(radius_));
    if (hitFraction_ < minHitFraction_ || weighted <= 0)
    {
        // the beam misses the metal: nothing is absorbed
        qi = 0;
        return tq;
    }

    const scalar target =
        absorptivity_*power_*lit*transmittedShare_
       *(scaleByHitFraction_ ? min(hitFraction_, scalar(1)) : scalar(1));
    qi *= target/weighted;
    q.correctBoundaryConditions();
    absorbedPower_ = gSum(qi*mesh_.V());
    return tq;
}


Foam::tmp<Foam::scalarField> Foam::meltdem::laserHeatSource::facingShape
(
    const volScalarField& alphaMetal,
    const point& x0
) const
{
    // <grad(alpha) . e> = |grad alpha| <-n_out . e>: the interface facing the beam
    const volVectorField gradAlpha(fvc::grad(alphaMetal));
    const vector& e = direction_;
    const vectorField& C = mesh_.C();
    tmp<scalarField> tshape(new scalarField(C.size(), Zero));
    scalarField& shape = tshape.ref();
    forAll(C, celli)
    {
        const scalar facing = gradAlpha[celli] & e;
        if (facing > 0)
        {
            vector d = C[celli] - x0;
            d -= (d & e)*e;
            shape[celli] = exp(-2*magSqr(d)/sqr(radius_))*facing;
        }
    }
    return tshape;
}


Foam::scalar Foam::meltdem::laserHeatSource::absorptivity(const scalar T) const
{
    if (!linearAbsorptivity_)
    {
        return absorptivity0_;
    }
    return max
    (
        min(absorptivity0_ + dAbsorptivitydT_*(T - Tabsorptivity_), absorptivityMax_),
        absorptivityMin_
    );
}


void Foam::meltdem::laserHeatSource::updateAbsorptivity
(
    const volScalarField& alphaMetal,
    const volScalarField& T
)
{
    if (!linearAbsorptivity_)
    {
        return;
    }
    // the beam's shape on the metal side of the surface facing it, as heatSource
    const scalarField w
    (
        facingShape(alphaMetal, position(mesh_.time().value()))
       *max(min(alphaMetal.primitiveField(), scalar(1)), scalar(0))*mesh_.V()
    );
    const scalar weight = gSum(w);
    const scalar weightedT = gSum(w*T.primitiveField());
    if (weight > 0)
    {
        absorptivity_ = absorptivity(weightedT/weight);
        Info<< "Laser: surface temperature " << weightedT/weight
            << " K, absorptivity " << absorptivity_ << endl;
    }
}

// ************************************************************************* //
