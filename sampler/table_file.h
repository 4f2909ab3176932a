#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <alignset/set_table.h>

#include "core/util/status.h"

namespace alignset::sampler {

// The table file's bytes (<alignset/set_table.h> describes the file):
//
//   0   magic "ALIGNTBL"
//   8   u32 format version: 1, or 2 where a section is partial
//   12  u32 section count
//   16  the directory, 20 bytes a section:
//         u32 N, u8 construction (ConstructionKind), u8 space (TableSpace),
//         u8 payload (1 generators, 2 points), u8 flags (version 1: 0;
//         version 2: 1 the keys are listed, 2 the lattices' sizes are),
//         u32 keys held, u64 payload bytes
//   ..  the payloads in directory order: the u32 keys and u32 sizes where
//       listed, then u32 generators, or binary64 x, y
//   end u32 CRC-32C of every byte before it
//
// Little-endian whatever the host. Pure: no files here (SetTable::Load and
// Save read and write them).
inline constexpr char kTableMagic[8] = {'A', 'L', 'I', 'G', 'N', 'T', 'B', 'L'};

// The version a table of these sections is written as: 1, or 2 where one is
// partial.
uint32_t FormatVersion(const std::vector<TableSection>& sections);
std::vector<uint8_t> EncodeTable(const std::vector<TableSection>& sections);
// DATA_LOSS for damage (empty, truncated, checksum), INVALID_ARGUMENT for a
// file that is whole but not a table this library reads (magic, version, a
// directory entry out of range); the message names the problem. The keys'
// contents are CheckSections' to check (SetTable::Parse runs both, each once).
StatusOr<std::vector<TableSection>> DecodeTable(std::span<const uint8_t> bytes);
// What a table's sections must hold, a file's or sections made in memory:
// N, construction and space in range, the space's key count (or listed keys
// in it, ascending), one generator coprime to N (or to the key's size, in
// [16, N]) per key of a lattice, N points in [0, 1) per key otherwise, and
// no two sections of one (N, construction, space).
Status CheckSections(const std::vector<TableSection>& sections);

}  // namespace alignset::sampler
