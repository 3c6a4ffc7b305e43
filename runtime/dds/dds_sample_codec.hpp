#pragma once
// SampleCodec (runtime/bus/sample_codec.hpp) by the generated Fast DDS type support: the bytes a
// DDS writer of our types puts on the wire. This header stays free of Fast DDS includes.

#include <memory>

#include "runtime/bus/sample_codec.hpp"

namespace robodds {

/// A codec of every IDL topic type (one type support per type, made on first use, thread-safe).
std::shared_ptr<const SampleCodec> make_dds_sample_codec();

/// Installs make_dds_sample_codec() as the program's codec (set_sample_codec()) unless one is
/// installed;
/// make_dds_bus() and make_raw_bus() call it, so every process that sets up
/// DDS, co-located or a host across processes, has it before its components are configured; and
/// the launcher's producer check (runtime/launch) before its dry configure of the components.
void install_dds_sample_codec();

}  // namespace robodds
