// What a file is by its content, whatever its name, and file text made fit for a message: so that a reader refuses
// a LAS file named .xyz as "a LAS file", not with the bytes it choked on.
#pragma once

#include <cstddef>
#include <string>

namespace gls
{

/// What the first `size` bytes of a file show it to be when it is not text: "a LAS file", "a LAZ file" (LAS with
/// compressed points), "a PLY file", "an E57 file", "a VTK XML file", "a ZIP archive", "a gzip archive", "a binary
/// file" (a NUL byte, or more than 1% of the bytes control characters other than tab and line ends); "" for text.
std::string binaryContentKind(const char* head, std::size_t size);

/// `text` with every byte that is not printable ASCII (control characters, bytes from 0x7f) written as \xNN, and cut
/// after `limit` characters ("..." then): file content quoted in a message stays one readable line.
std::string printableText(const std::string& text, std::size_t limit = 200);

} // namespace gls
