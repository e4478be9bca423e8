#include "convectiveTemperatureFvPatchScalarField.H"
#include "addToRunTimeSelectionTable.H"
#include "volFields.H"

namespace Foam
{

convectiveTemperatureFvPatchScalarField::convectiveTemperatureFvPatchScalarField
(
    const fvPatch& p,
    const DimensionedField<scalar, volMesh>& iF
)
:
    mixedFvPatchScalarField(p, iF),
    h_(p.size(), 0),
    Tinf_(p.size(), 0),
    kappaName_("kappa")
{
    refValue() = 0;
    refGrad() = 0;
    valueFraction() = 0;
}


convectiveTemperatureFvPatchScalarField::convectiveTemperatureFvPatchScalarField
(
    const fvPatch& p,
    const DimensionedField<scalar, volMesh>& iF,
    const dictionary& dict
)
:
    mixedFvPatchScalarField(p, iF),
    h_("h", dict, p.size()),
    Tinf_("Tinf", dict, p.size()),
    kappaName_(dict.getOrDefault<word>("kappa", "kappa"))
{
    checkCoefficients(dict);
    refValue() = Tinf_;
    refGrad() = 0;
    valueFraction() = 0;
    if (dict.found("value"))
    {
        fvPatchScalarField::operator=(scalarField("value", dict, p.size()));
    }
    else
    {
        fvPatchScalarField::operator=(Tinf_);
    }
}


convectiveTemperatureFvPatchScalarField::convectiveTemperatureFvPatchScalarField
(
    const convectiveTemperatureFvPatchScalarField& ptf,
    const fvPatch& p,
    const DimensionedField<scalar, volMesh>& iF,
    const fvPatchFieldMapper& mapper
)
:
    mixedFvPatchScalarField(ptf, p, iF, mapper),
    h_(ptf.h_, mapper),
    Tinf_(ptf.Tinf_, mapper),
    kappaName_(ptf.kappaName_)
{}


convectiveTemperatureFvPatchScalarField::convectiveTemperatureFvPatchScalarField
(
    const convectiveTemperatureFvPatchScalarField& ptf
)
:
    mixedFvPatchScalarField(ptf),
    h_(ptf.h_),
    Tinf_(ptf.Tinf_),
    kappaName_(ptf.kappaName_)
{}


convectiveTemperatureFvPatchScalarField::convectiveTemperatureFvPatchScalarField
(
    const convectiveTemperatureFvPatchScalarField& ptf,
    const DimensionedField<scalar, volMesh>& iF
)
:
    mixedFvPatchScalarField(ptf, iF),
    h_(ptf.h_),
    Tinf_(ptf.Tinf_),
    kappaName_(ptf.kappaName_)
{}


void convectiveTemperatureFvPatchScalarField::checkCoefficients(const dictionary& dict) const
{
    if (min(h_) < 0)
    {
        FatalIOErrorInFunction(dict)
            << "entry 'h' of patch " << patch().name() << " must be >= 0 (W/m2/K)"
            << exit(FatalIOError);
    }
    if (min(Tinf_) <= 0)
    {
        FatalIOErrorInFunction(dict)
            << "entry 'Tinf' of patch " << patch().name() << " must be > 0 (K)"
            << exit(FatalIOError);
    }
}


void convectiveTemperatureFvPatchScalarField::autoMap(const fvPatchFieldMapper& m)
{
    mixedFvPatchScalarField::autoMap(m);
    h_.autoMap(m);
    Tinf_.autoMap(m);
}


void convectiveTemperatureFvPatchScalarField::rmap
(
    const fvPatchScalarField& ptf,
    const labelList& addr
)
{
    mixedFvPatchScalarField::rmap(ptf, addr);
    const auto& tiptf = refCast<const convectiveTemperatureFvPatchScalarField>(ptf);
    h_.rmap(tiptf.h_, addr);
    Tinf_.rmap(tiptf.Tinf_, addr);
}


void convectiveTemperatureFvPatchScalarField::updateCoeffs()
{
    if (updated())
    {
        return;
    }
    const fvPatchScalarField& kappa =
        patch().lookupPatchField<volScalarField, scalar>(kappaName_);
    const scalarField kDelta(kappa*patch().deltaCoeffs());
    refValue() = Tinf_;
    refGrad() = 0;
    valueFraction() = h_/(h_ + kDelta + VSMALL);
    mixedFvPatchScalarField::updateCoeffs();
}


void convectiveTemperatureFvPatchScalarField::write(Ostream& os) const
{
    fvPatchScalarField::write(os);
    h_.writeEntry("h", os);
    Tinf_.writeEntry("Tinf", os);
    os.writeEntryIfDifferent<word>("kappa", "kappa", kappaName_);
    writeEntry("value", os);
}


makePatchTypeField(fvPatchScalarField, convectiveTemperatureFvPatchScalarField);

} // End namespace Foam
