#pragma once
// The tool version every result records and every case digest contains
// (config/case_identity.h). It moves whenever a parameter's, a setting's or a metric's meaning
// does, since a resumed folder keeps a finished case only while its digest is unchanged, and
// `run` refuses a folder another version wrote. Defined in version.cpp alone, so a bump rebuilds
// one file.
namespace lb {

extern const char* const kToolVersion;

}  // namespace lb
