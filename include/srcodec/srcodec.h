// srcodec: progressive mesh compression on adaptive semi-regular remeshes.
//
//   #include <srcodec/srcodec.h>
//
//   srcodec::StatusOr<srcodec::Mesh> mesh = srcodec::read_mesh("bunny.obj");
//   srcodec::EncodeOptions options;
//   options.rate = srcodec::Rate::psnr(70);
//   srcodec::StatusOr<std::vector<uint8_t>> file = srcodec::encode(*mesh, options);   // srcodec::encoder
//
//   srcodec::DecodeOptions at;
//   at.level = 2;
//   srcodec::StatusOr<srcodec::Decoded> d = srcodec::decode(file->data(), file->size(), at);  // srcodec::decoder
//
// Link srcodec::decoder for decode(), inspect(), truncate(), read_mesh() and
// write_mesh(); srcodec::encoder adds encode(). Every call returns a Status
// or StatusOr: check ok(), read message() when it is not. The WebAssembly
// build of the decoder (web/) has no files: read_mesh() and write_mesh() are
// left out of it.
#pragma once

#include <srcodec/decoder.h>
#include <srcodec/encoder.h>
#include <srcodec/mesh.h>
#include <srcodec/status.h>

namespace srcodec {

// "0.1.0": the library's version.
const char* version();

}  // namespace srcodec
