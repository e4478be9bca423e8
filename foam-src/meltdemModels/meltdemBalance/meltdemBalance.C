/*---------------------------------------------------------------------------*\
  MeltDEM: meltdemBalance function object (see meltdemBalance.H)
\*---------------------------------------------------------------------------*/

#include "meltdemBalance.H"
#include "volFields.H"
#include "surfaceFields.H"
#include "uniformDimensionedFields.H"
#include "emptyPolyPatch.H"
#include "IOdictionary.H"
#include "Time.H"
#include "addToRunTimeSelectionTable.H"
#include "exactScalar.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace functionObjects
{
    defineTypeNameAndDebug(meltdemBalance, 0);
    addToRunTimeSelectionTable(functionObject, meltdemBalance, dictionary);
}
}


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

void Foam::functionObjects::meltdemBalance::readProperties()
{
    IOdictionary transport
    (
        IOobject
        (
            "transportProperties",
            mesh_.time().constant(),
            mesh_,
            IOobject::MUST_READ,
            IOobject::NO_WRITE,
            false
        )
    );
    const wordList phases(transport.get<wordList>("phases"));
    if (phases.size() != 2)
    {
        FatalIOErrorInFunction(transport)
            << "phases: two phases (metal gas) expected, got " << phases
            << exit(FatalIOError);
    }
    metalName_ = phases[0];
    gasName_ = phases[1];
    const dictionary& m = transport.subDict(metalName_);
    const dictionary& g = transport.subDict(gasName_);
    rhoM_ = dimensionedScalar("rho", dimDensity, m).value();
    rhoG_ = dimensionedScalar("rho", dimDensity, g).value();
    nuM_ = m.found("nu") ? dimensionedScalar("nu", dimViscosity, m).value() : 0;
    nuG_ = g.found("nu") ? dimensionedScalar("nu", dimViscosity, g).value() : 0;

    // Thermal data are optional: without them the enthalpy columns are left out
    IOobject propsIO
    (
        "meltdemProperties",
        mesh_.time().constant(),
        mesh_,
        IOobject::MUST_READ,
        IOobject::NO_WRITE,
        false
    );
    hasThermo_ = false;
    if (propsIO.typeHeaderOk<IOdictionary>(true))
    {
        IOdictionary props(propsIO);
        // thermal data only where the energy equation runs (meltdemFoam reads
        // metal{} and gas{} only then)
        const bool energyOn =
            !props.isDict("physics")
         || props.subDict("physics").getOrDefault<bool>("energy", false);
        hasThermo_ = energyOn && props.isDict("metal") && props.isDict("gas");
    }
    if (hasThermo_)
    {
        IOdictionary props(propsIO);
        const dictionary& pm = props.subDict("metal");
        const dictionary& pg = props.subDict("gas");
        const dimensionSet dimCp(dimEnergy/dimMass/dimTemperature);
        const dimensionSet dimK(dimPower/dimLength/dimTemperature);
        cpM_ = dimensionedScalar("cp", dimCp, pm).value();
        kM_ = dimensionedScalar("k", dimK, pm).value();
        L_ = dimensionedScalar("L", dimEnergy/dimMass, pm).value();
        Ts_ = dimensionedScalar("Tsolidus", dimTemperature, pm).value();
        Tl_ = dimensionedScalar("Tliquidus", dimTemperature, pm).value();
        cpG_ = dimensionedScalar("cp", dimCp, pg).value();
        kG_ = dimensionedScalar("k", dimK, pg).value();
        if (Ts_ > Tl_)
        {
            FatalIOErrorInFunction(pm)
                << "Tsolidus " << Ts_ << " > Tliquidus " << Tl_
                << exit(FatalIOError);
        }
    }
}


Foam::tmp<Foam::scalarField>
Foam::functionObjects::meltdemBalance::alphaCells() const
{
    if (foundObject<volScalarField>(alphaName_))
    {
        return tmp<scalarField>
        (
            new scalarField
            (
                lookupObject<volScalarField>(alphaName_).primitiveField()
            )
        );
    }
    return tmp<scalarField>(new scalarField(mesh_.nCells(), 1.0));
}


Foam::scalar Foam::functionObjects::meltdemBalance::fl(const scalar T) const
{
    if (T >= Tl_) return 1;
    if (T <= Ts_) return 0;
    return (T - Ts_)/(Tl_ - Ts_);
}


void Foam::functionObjects::meltdemBalance::stored
(
    scalar& M,
    scalar& H,
    vector& P
) const
{
    const scalarField& V = mesh_.V();
    const tmp<scalarField> ta = alphaCells();
    const scalarField& a = ta();

    M = gSum(rhoM_*a*V);

    H = 0;
    if (energy_)
    {
        const scalarField& T = lookupObject<volScalarField>(TName_);
        scalarField f(T.size());
        if (foundObject<volScalarField>(fLName_))
        {
            f = lookupObject<volScalarField>(fLName_).primitiveField();
        }
        else
        {
            forAll(T, i) { f[i] = fl(T[i]); }
        }
        // the solver's heat capacity per volume when registered (any model of it)
        const scalarField C
        (
            foundObject<volScalarField>("rhoCp")
          ? scalarField(lookupObject<volScalarField>("rhoCp").primitiveField())
          : scalarField(a*rhoM_*cpM_ + (1 - a)*rhoG_*cpG_)
        );
        H = gSum((C*T + a*rhoM_*L_*f)*V);
    }

    P = Zero;
    if (momentum_)
    {
        const vectorField& U = lookupObject<volVectorField>(UName_);
        P = gSum((a*rhoM_ + (1 - a)*rhoG_)*V*U);
    }
}


void Foam::functionObjects::meltdemBalance::start()
{
    checkRenamed();
    energy_ = hasThermo_ && foundObject<volScalarField>(TName_);
    momentum_ = foundObject<volVectorField>(UName_);
    laser_ = energy_ && foundObject<volScalarField>(laserName_);
    evap_ = energy_ && foundObject<volScalarField>(evapName_);
    evapMass_ = foundObject<volScalarField::Internal>("evaporatedMassRate");
    physicsForce_ = momentum_ && foundObject<volVectorField::Internal>("physicsForce");

    scalar M, H;
    vector P;
    stored(M, H, P);
    if (!restoreState())
    {
        M0_ = M, H0_ = H, P0_ = P;
    }
    started_ = true;
    last_ = stepBudget();
    last_.M = M;
    last_.H = H;
    last_.P = P;
    lastIndex_ = time_.timeIndex();

    if (log)
    {
        Info<< type() << " " << name() << ": alpha "
            << (foundObject<volScalarField>(alphaName_)
                ? string(alphaName_) : string("none (all metal)"))
            << ", enthalpy " << (energy_ ? "on" : "off")
            << ", momentum " << (momentum_ ? "on" : "off")
            << ", laser " << (laser_ ? "on" : "off")
            << ", evaporation " << (evap_ ? "on" : "off")
            << (evapMass_ ? " with mass loss" : "") << nl;
    }

    // sources() reduces over the ranks: every rank evaluates it before the master writes
    scalar laserP = 0, evapP = 0;
    sources(laserP, evapP);

    if (!Pstream::master()) return;

    const fileName dir
    (
        time_.globalPath()/functionObject::outputPrefix/name()
       /time_.timeName()
    );
    mkDir(dir);
    fileName file(dir/"balance.csv");
    if (isFile(file))
    {
        file = dir/("balance_" + time_.timeName() + ".csv");
    }
    os_.reset(new OFstream(file));
    OFstream& os = os_();
    os.precision(15);

    const char* xyz[3] = {"_x", "_y", "_z"};
    os  << "time,deltaT,metalMass";
    if (energy_) os << ",enthalpy";
    if (momentum_) for (int c = 0; c < 3; ++c) os << ",momentum" << xyz[c];
    if (laser_) os << ",laserPower";
    if (evap_) os << ",evaporationPower";
    forAll(patches_, pi)
    {
        const word& pn = mesh_.boundaryMesh()[patches_[pi]].name();
        os << ",massIn_" << pn;
        if (energy_) os << ",enthalpyAdvIn_" << pn << ",enthalpyCondIn_" << pn;
        if (momentum_)
        {
            for (int c = 0; c < 3; ++c) os << ",momentumIn_" << pn << xyz[c];
        }
    }
    os << ",massIn_cum";
    if (energy_) os << ",enthalpyIn_cum";
    if (laser_) os << ",laserEnergy_cum";
    if (evap_) os << ",evaporationEnergy_cum";
    if (momentum_)
    {
        for (int c = 0; c < 3; ++c) os << ",momentumIn_cum" << xyz[c];
        for (int c = 0; c < 3; ++c) os << ",gravityImpulse_cum" << xyz[c];
    }
    os << ",massError,massErrorRel";
    if (energy_) os << ",enthalpyError,enthalpyErrorRel,enthalpyErrorRelExchanged";
    if (momentum_)
    {
        for (int c = 0; c < 3; ++c) os << ",momentumError" << xyz[c];
        os << ",momentumErrorRel";
    }
    if (evapMass_)
    {
        os << ",evaporatedMass_cum";
        if (energy_) os << ",evaporatedEnthalpy_cum";
        if (momentum_) for (int c = 0; c < 3; ++c) os << ",evaporatedMomentum_cum" << xyz[c];
    }
    if (physicsForce_) for (int c = 0; c < 3; ++c) os << ",physicsForceImpulse_cum" << xyz[c];
    os << nl;

    // the start state as first row, flows zero (a resumed run: its errors so far)
    const label nPer = 1 + (energy_ ? 2 : 0) + (momentum_ ? 3 : 0);
    writeRow(0, M, H, P, laserP, evapP, scalarList(nPer*patches_.size(), 0.0), errors(M, H, P));
}




void Foam::functionObjects::meltdemBalance::saveState() const
{
    IOdictionary state
    (
        IOobject
        (
            name(), time_.timeName(), "uniform"/word(typeName), time_,
            IOobject::NO_READ, IOobject::NO_WRITE, false
        )
    );
    const scalar scalars[] =
    {
        M0_, H0_, P0_.x(), P0_.y(), P0_.z(), massIn_, enthalpyIn_, laserE_, evapE_,
        enthalpyAbs_, momentumIn_.x(), momentumIn_.y(), momentumIn_.z(), gravityImp_.x(),
        gravityImp_.y(), gravityImp_.z(), momentumAbs_, exchangeMass_, exchangeEnthalpy_,
        exchangeMomentum_.x(), exchangeMomentum_.y(), exchangeMomentum_.z(),
        evaporatedMass_, evaporatedEnthalpy_, evaporatedMomentum_.x(), evaporatedMomentum_.y(),
        evaporatedMomentum_.z(), physicsForceImp_.x(), physicsForceImp_.y(), physicsForceImp_.z()
    };
    List<string> values(label(sizeof scalars/sizeof scalars[0]));
    forAll(values, i) values[i] = meltdem::exactScalar(scalars[i]);
    state.add("time", meltdem::exactScalar(time_.value()));
    state.add("integrals", values);
    state.regIOobject::writeObject
    (
        IOstream::ASCII, IOstream::currentVersion, IOstream::UNCOMPRESSED, true
    );
}


bool Foam::functionObjects::meltdemBalance::restoreState()
{
    IOdictionary state
    (
        IOobject
        (
            name(), time_.timeName(), "uniform"/word(typeName), time_,
            IOobject::READ_IF_PRESENT, IOobject::NO_WRITE, false
        )
    );
    if (!state.found("integrals")) return false;
    const List<string> values(state.get<List<string>>("integrals"));
    // (22: written before evaporation's mass loss was booked, 27: before the physics force)
    if (values.size() != 22 && values.size() != 27 && values.size() != 30)
    {
        FatalIOErrorInFunction(state)
            << "integrals: 30 (or 27, 22) values expected, found " << values.size()
            << exit(FatalIOError);
    }
    scalarList v(values.size());
    forAll(values, i) v[i] = meltdem::readExactScalar(state, values[i], "integrals");
    M0_ = v[0]; H0_ = v[1]; P0_ = vector(v[2], v[3], v[4]);
    massIn_ = v[5]; enthalpyIn_ = v[6]; laserE_ = v[7]; evapE_ = v[8];
    enthalpyAbs_ = v[9]; momentumIn_ = vector(v[10], v[11], v[12]);
    gravityImp_ = vector(v[13], v[14], v[15]); momentumAbs_ = v[16];
    exchangeMass_ = v[17]; exchangeEnthalpy_ = v[18];
    exchangeMomentum_ = vector(v[19], v[20], v[21]);
    if (v.size() >= 27)
    {
        evaporatedMass_ = v[22]; evaporatedEnthalpy_ = v[23];
        evaporatedMomentum_ = vector(v[24], v[25], v[26]);
    }
    if (v.size() == 30)
    {
        physicsForceImp_ = vector(v[27], v[28], v[29]);
    }
    if (log)
    {
        Info<< type() << " " << name() << ": continues the balance written at t = "
            << time_.timeName() << " (" << state.objectPath() << ")" << nl;
    }
    return true;
}


Foam::scalar Foam::functionObjects::meltdemBalance::exchangedRel
(
    const scalar err,
    const scalar scale
)
{
    // nothing exchanged and nothing changed: no error to speak of
    if (scale < VSMALL) return err == 0 ? 0 : err/VSMALL;
    return err/scale;
}


Foam::functionObjects::meltdemBalance::balanceErrors
Foam::functionObjects::meltdemBalance::errors
(
    const scalar M,
    const scalar H,
    const vector& P
) const
{
    balanceErrors e;
    e.mass = (M - M0_) - massIn_ - exchangeMass_ + evaporatedMass_;
    // relative to the larger of the metal at the start and now (a run may start empty)
    e.massRel = e.mass/max(max(mag(M0_), mag(M)), VSMALL);
    e.H = (H - H0_) - enthalpyIn_ - laserE_ + evapE_ - exchangeEnthalpy_ + evaporatedEnthalpy_;
    e.HRel = e.H/max(mag(H0_), VSMALL);
    e.HRelExchanged = exchangedRel(e.H, max(mag(H - H0_), enthalpyAbs_));
    e.P =
        (P - P0_) - momentumIn_ - gravityImp_ - exchangeMomentum_ + evaporatedMomentum_
      - physicsForceImp_;
    e.PRel = exchangedRel(mag(e.P), max(mag(P - P0_), momentumAbs_));
    return e;
}


Foam::vector Foam::functionObjects::meltdemBalance::gravity() const
{
    // solvers register g on Time (meshObjects::gravity), older ones on the mesh
    typedef uniformDimensionedVectorField gField;
    if (time_.foundObject<gField>("g"))
    {
        return time_.lookupObject<gField>("g").value();
    }
    if (foundObject<gField>("g"))
    {
        return lookupObject<gField>("g").value();
    }
    IOobject gIO
    (
        "g",
        time_.constant(),
        mesh_,
        IOobject::MUST_READ,
        IOobject::NO_WRITE,
        false
    );
    if (gIO.typeHeaderOk<gField>(true))
    {
        return gField(gIO).value();
    }
    return Zero;
}


void Foam::functionObjects::meltdemBalance::sources
(
    scalar& laserP,
    scalar& evapP
) const
{
    const scalarField& V = mesh_.V();
    laserP = 0;
    evapP = 0;
    if (laser_ && foundObject<volScalarField>(laserName_))
    {
        laserP = gSum(lookupObject<volScalarField>(laserName_).primitiveField()*V);
    }
    if (evap_ && foundObject<volScalarField>(evapName_))
    {
        evapP = gSum(lookupObject<volScalarField>(evapName_).primitiveField()*V);
    }
}


void Foam::functionObjects::meltdemBalance::writeRow
(
    const scalar dt,
    const scalar M,
    const scalar H,
    const vector& P,
    const scalar laserP,
    const scalar evapP,
    const UList<scalar>& patchCols,
    const balanceErrors& err
)
{
    if (!Pstream::master() || !os_.valid()) return;

    OFstream& os = os_();
    os << time_.value() << ',' << dt << ',' << M;
    if (energy_) os << ',' << H;
    if (momentum_) os << ',' << P.x() << ',' << P.y() << ',' << P.z();
    if (laser_) os << ',' << laserP;
    if (evap_) os << ',' << evapP;
    forAll(patchCols, i) os << ',' << patchCols[i];
    os << ',' << massIn_;
    if (energy_) os << ',' << enthalpyIn_;
    if (laser_) os << ',' << laserE_;
    if (evap_) os << ',' << evapE_;
    if (momentum_)
    {
        for (direction c = 0; c < 3; ++c) os << ',' << momentumIn_[c];
        for (direction c = 0; c < 3; ++c) os << ',' << gravityImp_[c];
    }
    os << ',' << err.mass << ',' << err.massRel;
    if (energy_) os << ',' << err.H << ',' << err.HRel << ',' << err.HRelExchanged;
    if (momentum_)
    {
        for (direction c = 0; c < 3; ++c) os << ',' << err.P[c];
        os << ',' << err.PRel;
    }
    if (evapMass_)
    {
        os << ',' << evaporatedMass_;
        if (energy_) os << ',' << evaporatedEnthalpy_;
        if (momentum_) for (direction c = 0; c < 3; ++c) os << ',' << evaporatedMomentum_[c];
    }
    if (physicsForce_) for (direction c = 0; c < 3; ++c) os << ',' << physicsForceImp_[c];
    os << endl;
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::functionObjects::meltdemBalance::meltdemBalance
(
    const word& name,
    const Time& runTime,
    const dictionary& dict
)
:
    fvMeshFunctionObject(name, runTime, dict),
    rhoM_(0), rhoG_(0), nuM_(0), nuG_(0),
    hasThermo_(false),
    cpM_(0), cpG_(0), kM_(0), kG_(0), L_(0), Ts_(0), Tl_(0),
    energy_(false), momentum_(false), laser_(false), evap_(false), evapMass_(false),
    physicsForce_(false),
    started_(false),
    M0_(0), H0_(0), P0_(Zero),
    massIn_(0), enthalpyIn_(0), laserE_(0), evapE_(0), enthalpyAbs_(0),
    momentumIn_(Zero), gravityImp_(Zero), momentumAbs_(0),
    lastIndex_(-1),
    exchangeMass_(0), exchangeEnthalpy_(0), exchangeMomentum_(Zero),
    evaporatedMass_(0), evaporatedEnthalpy_(0), evaporatedMomentum_(Zero),
    physicsForceImp_(Zero)
{
    readProperties();
    read(dict);

    DynamicList<label> ids;
    forAll(mesh_.boundaryMesh(), patchi)
    {
        const polyPatch& pp = mesh_.boundaryMesh()[patchi];
        if (!pp.coupled() && !isA<emptyPolyPatch>(pp)) ids.append(patchi);
    }
    patches_.transfer(ids);

    // The solver's fields exist when function objects are constructed (first
    // runTime.run()); otherwise start at the first execute.
    if
    (
        foundObject<volScalarField>(alphaName_)
     || foundObject<volScalarField>(TName_)
     || foundObject<volVectorField>(UName_)
    )
    {
        start();
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

bool Foam::functionObjects::meltdemBalance::read(const dictionary& dict)
{
    fvMeshFunctionObject::read(dict);
    // each field name, its entry kept when it names another field than the default
    renamed_ = dictionary(dict.name());
    const auto fieldName = [&](const word& key, const word& def)
    {
        const word field = dict.getOrDefault<word>(key, def);
        if (field != def) renamed_.add(*dict.findEntry(key));
        return field;
    };
    alphaName_ = fieldName("alpha", "alpha." + metalName_);
    TName_ = fieldName("T", "T");
    UName_ = fieldName("U", "U");
    phiName_ = fieldName("phi", "phi");
    pName_ = fieldName("p", "p");
    fLName_ = fieldName("liquidFraction", "liquidFraction");
    laserName_ = fieldName("laserHeatSource", "laserHeatSource");
    evapName_ = fieldName("evaporationHeatLoss", "evaporationHeatLoss");
    return true;
}


void Foam::functionObjects::meltdemBalance::checkRenamed() const
{
    for (const entry& e : renamed_)
    {
        const word field(e.stream());
        if (!obr_.found(field))
        {
            FatalIOErrorInFunction(renamed_)
                << type() << " " << name() << ": " << e.keyword() << " "
                << field << ": no field " << field << " (fields: "
                << obr_.sortedNames<volScalarField>() << " "
                << obr_.sortedNames<volVectorField>() << " "
                << obr_.sortedNames<surfaceScalarField>() << ")"
                << exit(FatalIOError);
        }
    }
}


bool Foam::functionObjects::meltdemBalance::execute()
{
    if (!started_)
    {
        start();
        return true;
    }
    // once per time step (execute may be called again at the end of the run)
    if (time_.timeIndex() == lastIndex_) return true;
    lastIndex_ = time_.timeIndex();

    const scalar dt = time_.deltaTValue();
    const scalarField& V = mesh_.V();
    const tmp<scalarField> ta = alphaCells();
    const scalarField& a = ta();

    const bool hasAlpha = foundObject<volScalarField>(alphaName_);
    const volScalarField* alphaPtr =
        hasAlpha ? &lookupObject<volScalarField>(alphaName_) : nullptr;
    const word alphaPhiName("alphaPhi0." + metalName_);
    const surfaceScalarField* phiPtr =
        foundObject<surfaceScalarField>(phiName_)
      ? &lookupObject<surfaceScalarField>(phiName_) : nullptr;
    const surfaceScalarField* alphaPhiPtr =
        foundObject<surfaceScalarField>(alphaPhiName)
      ? &lookupObject<surfaceScalarField>(alphaPhiName) : nullptr;
    const surfaceScalarField* rhoPhiPtr =
        foundObject<surfaceScalarField>("rhoPhi")
      ? &lookupObject<surfaceScalarField>("rhoPhi") : nullptr;
    const volScalarField* TPtr =
        energy_ ? &lookupObject<volScalarField>(TName_) : nullptr;
    const volScalarField* fLPtr =
        energy_ && foundObject<volScalarField>(fLName_)
      ? &lookupObject<volScalarField>(fLName_) : nullptr;
    const volScalarField* kappaPtr =
        energy_ && foundObject<volScalarField>("kappa")
      ? &lookupObject<volScalarField>("kappa") : nullptr;
    const volVectorField* UPtr =
        momentum_ ? &lookupObject<volVectorField>(UName_) : nullptr;
    const volScalarField* pPtr =
        momentum_ && foundObject<volScalarField>(pName_)
      ? &lookupObject<volScalarField>(pName_) : nullptr;

    scalar M, H; vector P;
    stored(M, H, P);

    scalar laserP = 0, evapP = 0;
    sources(laserP, evapP);
    vector gravityF(Zero);
    if (momentum_)
    {
        gravityF = gSum((a*rhoM_ + (1 - a)*rhoG_)*V)*gravity();
    }

    // per-patch flows into the domain
    DynamicList<scalar> patchCols;
    scalar massStep = 0, enthalpyStep = 0, enthalpyAbsStep = 0;
    vector momentumStep(Zero);
    scalar momentumAbsStep = 0;
    forAll(patches_, pi)
    {
        const label patchi = patches_[pi];
        const fvPatch& fp = mesh_.boundary()[patchi];
        const label n = fp.size();
        const scalarField ab
        (
            alphaPtr ? scalarField(alphaPtr->boundaryField()[patchi])
                     : scalarField(n, 1.0)
        );
        const scalarField phib
        (
            phiPtr ? scalarField(phiPtr->boundaryField()[patchi])
                   : scalarField(n, 0.0)
        );
        const scalarField aphib
        (
            alphaPhiPtr ? scalarField(alphaPhiPtr->boundaryField()[patchi])
                        : scalarField(phib*ab)
        );

        const scalar mIn = -gSum(rhoM_*aphib);
        patchCols.append(mIn);
        massStep += mIn;

        if (energy_)
        {
            const fvPatchScalarField& Tb = TPtr->boundaryField()[patchi];
            scalarField fb(n);
            if (fLPtr)
            {
                fb = fLPtr->boundaryField()[patchi];
            }
            else
            {
                forAll(fb, i) { fb[i] = fl(Tb[i]); }
            }
            // gas mass flux: from rhoPhi when registered, since the energy
            // equation ran with the fluxes that moved alpha (phi changes after
            // it, in the pressure correction)
            const scalarField gasMassFlux
            (
                rhoPhiPtr
              ? scalarField(rhoPhiPtr->boundaryField()[patchi] - rhoM_*aphib)
              : scalarField((phib - aphib)*rhoG_)
            );
            const scalar advIn = -gSum
            (
                (aphib*rhoM_*cpM_ + gasMassFlux*cpG_)*Tb
              + aphib*rhoM_*L_*fb
            );
            // the solver's conductivity when registered (its face value on a
            // boundary is the patch value)
            const scalarField kb
            (
                kappaPtr ? scalarField(kappaPtr->boundaryField()[patchi])
                         : scalarField(ab*kM_ + (1 - ab)*kG_)
            );
            const scalar condIn = gSum(kb*Tb.snGrad()*fp.magSf());
            patchCols.append(advIn);
            patchCols.append(condIn);
            enthalpyStep += advIn + condIn;
            enthalpyAbsStep += mag(advIn) + mag(condIn);
        }

        if (momentum_)
        {
            const fvPatchVectorField& Ub = UPtr->boundaryField()[patchi];
            const scalarField rhob(ab*rhoM_ + (1 - ab)*rhoG_);
            const scalarField rhoPhib
            (
                rhoPhiPtr ? scalarField(rhoPhiPtr->boundaryField()[patchi])
                          : scalarField(rhob*phib)
            );
            const scalarField mub(ab*rhoM_*nuM_ + (1 - ab)*rhoG_*nuG_);
            vector mom = -gSum(rhoPhib*Ub) + gSum(mub*fp.magSf()*Ub.snGrad());
            if (pPtr)
            {
                mom -= gSum(pPtr->boundaryField()[patchi]*fp.Sf());
            }
            for (direction c = 0; c < 3; ++c) patchCols.append(mom[c]);
            momentumStep += mom;
            momentumAbsStep += mag(mom);
        }
    }

    // matter the coupled particles handed over (net of what they took), registered by
    // the particle coupling as rates per volume
    scalar exMass = 0, exH = 0;
    vector exP(Zero);
    if (foundObject<volScalarField::Internal>("particleMassSource"))
    {
        exMass = dt*gSum(lookupObject<volScalarField::Internal>("particleMassSource").field()*V);
    }
    if (foundObject<volScalarField::Internal>("particleEnthalpySource"))
    {
        exH = dt*gSum(lookupObject<volScalarField::Internal>("particleEnthalpySource").field()*V);
    }
    if (foundObject<volVectorField::Internal>("particleMomentumSource"))
    {
        exP = dt*gSum(lookupObject<volVectorField::Internal>("particleMomentumSource").field()*V);
    }
    exchangeMass_ += exMass;
    exchangeEnthalpy_ += exH;
    exchangeMomentum_ += exP;
    enthalpyAbs_ += mag(exH);
    momentumAbs_ += mag(exP);

    // what evaporation took out of the metal (massLoss on), rates per volume
    scalar evMass = 0, evH = 0;
    vector evP(Zero);
    if (evapMass_)
    {
        evMass = dt*gSum(lookupObject<volScalarField::Internal>("evaporatedMassRate").field()*V);
        if (energy_ && foundObject<volScalarField::Internal>("evaporatedEnthalpyRate"))
        {
            evH = dt*gSum(lookupObject<volScalarField::Internal>("evaporatedEnthalpyRate").field()*V);
        }
        if (momentum_ && foundObject<volVectorField::Internal>("evaporatedMomentumRate"))
        {
            evP = dt*gSum(lookupObject<volVectorField::Internal>("evaporatedMomentumRate").field()*V);
        }
    }
    evaporatedMass_ += evMass;
    evaporatedEnthalpy_ += evH;
    evaporatedMomentum_ += evP;
    enthalpyAbs_ += mag(evH);
    momentumAbs_ += mag(evP);

    // the solver's physics terms and surface force (meltdemFoam's physicsForce)
    vector forceP(Zero);
    if (physicsForce_)
    {
        forceP = dt*gSum(lookupObject<volVectorField::Internal>("physicsForce").field()*V);
    }
    physicsForceImp_ += forceP;
    momentumAbs_ += mag(forceP);

    last_.M = M;
    last_.H = H;
    last_.P = P;
    last_.dt = dt;
    last_.massIn = dt*massStep;
    last_.enthalpyIn = dt*enthalpyStep;
    last_.momentumIn = dt*momentumStep;
    last_.laserE = dt*laserP;
    last_.evapE = dt*evapP;
    last_.gravityImpulse = dt*gravityF;
    last_.exchangeMass = exMass;
    last_.exchangeEnthalpy = exH;
    last_.exchangeMomentum = exP;
    last_.evaporatedMass = evMass;
    last_.evaporatedEnthalpy = evH;
    last_.evaporatedMomentum = evP;
    last_.physicsForceImpulse = forceP;

    massIn_ += dt*massStep;
    enthalpyIn_ += dt*enthalpyStep;
    laserE_ += dt*laserP;
    evapE_ += dt*evapP;
    enthalpyAbs_ += dt*(enthalpyAbsStep + mag(laserP) + mag(evapP));
    momentumIn_ += dt*momentumStep;
    gravityImp_ += dt*gravityF;
    momentumAbs_ += dt*(momentumAbsStep + mag(gravityF));

    const balanceErrors err(errors(M, H, P));
    if (log)
    {
        Info<< type() << " " << name() << ": metal mass " << M
            << " rel. error " << err.massRel;
        if (energy_)
        {
            Info<< ", enthalpy " << H << " rel. error " << err.HRel
                << " (" << err.HRelExchanged << " of the heat exchanged)";
        }
        if (momentum_) Info<< ", momentum rel. error " << err.PRel;
        Info<< nl;
    }

    writeRow(dt, M, H, P, laserP, evapP, patchCols, err);
    if (time_.writeTime())
    {
        saveState();
    }
    return true;
}


bool Foam::functionObjects::meltdemBalance::write()
{
    return true;
}


// ************************************************************************* //
