#pragma once
// The provenance every JSON file the tools write carries: which trnkit version and git commit
// produced it, so a number in a report can be traced to the code. One place, so the field names
// cannot drift between writers. A template over the JSON type keeps nlohmann out of this
// installed header; readers ignore these fields (files written before them still read).
#include <string>
#include "trn/build_info.hpp"

namespace trn::io {

template <class Json>
void add_provenance(Json& object) {
    const BuildInfo& build = build_info();
    object["trnkit_version"] = std::string(build.version);
    object["git_commit"] = std::string(build.git_commit);
}

}  // namespace trn::io
