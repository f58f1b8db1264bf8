// The data panel's raw-layout fields: filled from a layout given before or from the file name,
// turned into the RawLayout the render worker opens the file with.
#include "ui/raw_layout_fields.h"

#include "core/volume/readers/raw_reader.h"

namespace kdswap {
namespace {

//! Overwrites the fields `layout` sets; the others keep their values.
void apply(const RawLayout& layout, RawLayoutFields& fields) {
  if (layout.dims)
    for (int i = 0; i < 3; ++i) fields.dims[i] = (*layout.dims)[i];
  // A type name the core does not know keeps the field: opening would refuse it anyway.
  if (layout.type)
    if (const auto type = parseScalarType(*layout.type)) fields.type = *type;
  if (layout.bigEndian) fields.bigEndian = *layout.bigEndian;
  if (layout.spacing)
    for (int i = 0; i < 3; ++i) fields.spacing[i] = (*layout.spacing)[i];
  fields.headerBytes = layout.headerBytes;
}

}  // namespace

std::optional<RawLayoutFields> knownRawLayout(const std::string& path, const std::map<std::string, RawLayout>& given) {
  const RawLayout named = rawLayoutFromName(path);
  const auto it = given.find(path);
  if (it == given.end() && !named.dims && !named.type) return std::nullopt;
  // Like the reader: the given layout overrides the name, the name fills what it leaves out.
  RawLayoutFields fields;
  apply(named, fields);
  if (it != given.end()) apply(it->second, fields);
  return fields;
}

RawLayout toRawLayout(const RawLayoutFields& fields) {
  RawLayout layout;
  layout.dims = glm::ivec3(fields.dims[0], fields.dims[1], fields.dims[2]);
  layout.type = std::string(scalarTypeName(fields.type));
  layout.bigEndian = fields.bigEndian;
  layout.spacing = glm::vec3(fields.spacing[0], fields.spacing[1], fields.spacing[2]);
  layout.headerBytes = fields.headerBytes;
  return layout;
}

}  // namespace kdswap
