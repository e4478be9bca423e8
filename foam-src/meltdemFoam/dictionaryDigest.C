// dictionary::digest() through a string stream. The library's version writes into OSHA1stream,
// whose stream buffer has no overflow(): built with GCC 14 (Debian trixie's OpenFOAM v1912) a
// single character fails the stream, and every case with a "functions" entry stops at its first
// step (functionObjectList::read digests each entry). Defined in the executable, this definition
// takes the library's place; the digest is the SHA1 of the same text.
#include "dictionary.H"
#include "OStringStream.H"
#include "SHA1.H"

Foam::SHA1Digest Foam::dictionary::digest() const
{
    OStringStream os;
    for (const entry& e : *this)
    {
        os << e;
    }
    return SHA1(os.str()).digest();
}
