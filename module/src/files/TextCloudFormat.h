// The text parser of a file's format, chosen by its content (gls::textCloudFormat), for readPointTextFile, and the
// PTX header test it asks.
#pragma once

#include "gls/PointTextParser.h"

namespace gls
{
namespace pointtext
{

/// `text` parsed by parsePcd, parsePtx or parsePointText as textCloudFormat tells; the layout says "a PCL PCD file by
/// its content: ..." or "a Leica PTX file by its content: ..." for the first two.
PointText parseTextCloud(const char* text, std::size_t size);

/// Whether the text begins with a PTX scan's header as parsePtx reads it (its column and row counts, the scanner's
/// position and axes, the registration matrix). Defined beside parsePtx.
bool beginsWithPtxHeader(const char* text, std::size_t size);

} // namespace pointtext
} // namespace gls
