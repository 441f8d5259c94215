// The text parser of a file's format, chosen by its content (gls::textCloudFormat), for readPointTextFile.
#pragma once

#include "gls/PointTextParser.h"

namespace gls
{
namespace pointtext
{

/// `text` parsed by parsePcd, parsePtx or parsePointText as textCloudFormat tells; the layout says "a PCL PCD file by
/// its content: ..." or "a Leica PTX file by its content: ..." for the first two.
PointText parseTextCloud(const char* text, std::size_t size);

} // namespace pointtext
} // namespace gls
