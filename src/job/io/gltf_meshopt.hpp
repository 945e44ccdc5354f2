// gltf_meshopt.hpp - glTF's EXT_meshopt_compression: buffer views compressed with meshoptimizer's codecs.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace tinygltf {
class Model;
}  // namespace tinygltf

namespace facet {

// Whether this build decodes EXT_meshopt_compression (the browser page's, FACET_NO_MESHOPT, does not).
bool decodes_meshopt();

// tinygltf reads every buffer a file lists, and cannot read the placeholder buffer that compressed buffer views
// name as their own: it has no uri (in a GLB, tinygltf copies the BIN chunk into it, and fails when the
// placeholder's byteLength, that of the uncompressed data, is larger: "Invalid `byteLength'"). In a file that uses
// EXT_meshopt_compression, each buffer with no uri (other than a GLB's BIN chunk, buffer 0) and, when this build
// decodes the extension, each buffer the extension marks as a fallback (even one with a uri: its data is not
// needed) is handed to tinygltf as one byte of embedded data instead. Returns the rewritten .gltf text or GLB, or
// nullopt when nothing changes.
std::optional<std::string> without_meshopt_placeholders(std::string_view bytes, bool binary);

// Decodes each buffer view compressed with EXT_meshopt_compression that a mesh's accessors read into a buffer of
// its own, appended to the model, and points the view at it, so accessors read the decoded bytes. Every value of
// the extension is checked first; throws InputError(source, "bufferView N: EXT_meshopt_compression: <problem>")
// for a value out of range, a stream the decoder refuses, or decoded data past the limits (at most 64 times the
// compressed size, which the codecs cannot exceed, and in all at most 64 times the file's buffers and 1 GiB).
// A build without the decoder refuses a compressed view unless its own buffer holds the uncompressed data.
void decode_meshopt(tinygltf::Model& model, const std::string& source);

}  // namespace facet
