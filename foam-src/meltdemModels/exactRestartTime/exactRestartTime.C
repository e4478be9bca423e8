#include "exactRestartTime.H"

#include "IOdictionary.H"
#include "exactScalar.H"



Foam::meltdem::exactRestartTime::exactRestartTime
(
    const word& ctrlDictName,
    const argList& args
)
:
    Time(ctrlDictName, args),
    origin_(startTime_),
    writeIndexOffset_(0),
    restored_(false)
{
    restore();
}


void Foam::meltdem::exactRestartTime::restore()
{
    IOdictionary exact
    (
        IOobject
        (
            "exactTime", timeName(), "uniform", *this,
            IOobject::READ_IF_PRESENT, IOobject::NO_WRITE, false
        )
    );
    if (!exact.found("value")) return;

    // a record of another time (a renamed folder) is not this start
    const scalar value = readExactScalar(exact, "value");
    if (timeName(value) != timeName())
    {
        WarningInFunction
            << exact.objectPath() << " holds t = " << value << ", not the start time "
            << timeName() << ": not used" << endl;
        return;
    }
    setTime(value, timeIndex());
    deltaT_ = readExactScalar(exact, "deltaT");
    deltaTSave_ = deltaT_;
    deltaT0_ = readExactScalar(exact, "deltaT0");
    origin_ = readExactScalar(exact, "origin");
    if (writeControl_ == wcAdjustableRunTime || writeControl_ == wcRunTime)
    {
        writeIndexOffset_ = label((startTime_ - origin_)/writeInterval_ + 0.5);
    }
    restored_ = true;
    Info<< "Time: resumed exactly at t = " << exactScalar(value) << " (" << value
        << " s), deltaT " << deltaT_ << " s, write times counted from t = " << origin_
        << " s" << nl << endl;
}


void Foam::meltdem::exactRestartTime::adjustDeltaTFromOrigin()
{
    if (writeControl_ != wcAdjustableRunTime) return;
    const scalar timeToNextWrite = max
    (
        0.0,
        (writeTimeIndex_ + writeIndexOffset_ + 1)*writeInterval_ - (value() - origin_)
    );
    const scalar nSteps = timeToNextWrite/deltaT_;
    // as Time::adjustDeltaT: at least one step, growth at most 2, shrinking at most 5
    if (nSteps < labelMax)
    {
        const label nStepsToNextWrite = max(1, round(nSteps));
        const scalar newDeltaT = timeToNextWrite/nStepsToNextWrite;
        if (newDeltaT >= deltaT_)
        {
            deltaT_ = min(newDeltaT, 2.0*deltaT_);
        }
        else
        {
            deltaT_ = max(newDeltaT, 0.2*deltaT_);
        }
    }
}


void Foam::meltdem::exactRestartTime::setDeltaT
(
    const dimensionedScalar& deltaT,
    const bool adjust
)
{
    setDeltaT(deltaT.value(), adjust);
}


void Foam::meltdem::exactRestartTime::setDeltaT(const scalar deltaT, const bool adjust)
{
    Time::setDeltaT(deltaT, false);
    if (adjust) adjustDeltaTFromOrigin();
}


bool Foam::meltdem::exactRestartTime::writeTimeDict() const
{
    if (!Time::writeTimeDict()) return false;
    IOdictionary exact
    (
        IOobject
        (
            "exactTime", timeName(), "uniform", *this,
            IOobject::NO_READ, IOobject::NO_WRITE, false
        )
    );
    exact.add("value", exactScalar(value()));
    exact.add("deltaT", exactScalar(deltaT_));
    exact.add("deltaT0", exactScalar(deltaT0_));
    exact.add("origin", exactScalar(origin_));
    return exact.regIOobject::writeObject
    (
        IOstream::ASCII, IOstream::currentVersion, IOstream::UNCOMPRESSED, true
    );
}
