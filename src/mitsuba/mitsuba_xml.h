// Mitsuba 3 scene files (XML, and the 0.5/0.6 files Mitsuba 3 upgrades) translated into our
// JSON scene document, which the JSON loader then builds: one scene model, and `convert`
// writes exactly what a render reads. docs/scene-format.md, "Mitsuba 3 XML files", says what
// maps to what.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace wavetrace {

struct MitsubaDocument {
    nlohmann::json scene;  // our JSON scene; file names relative to the XML file's folder
    // For each entry of scene["objects"]: the XML element it came from ("a.xml:12").
    std::vector<std::string> object_places;
    // For each entry of scene["lights"]: the element it came from; the background's, if any.
    std::vector<std::string> light_places;
    std::string background_place;
};

// Reads `path` with its includes; `params` are the -D name=value overrides of <default>s.
// Throws SceneError naming the file and line on bad input; `warn` gets, for each element it
// cannot represent, a message naming its place, the plugin and the property
// ("a.xml:12: warning: sensor: near_clip and far_clip are not supported; ..."). Every file it
// reads (includes, spectra) must lie inside `asset_root`, if not empty.
MitsubaDocument translate_mitsuba_xml(const std::filesystem::path& path,
                                      const std::map<std::string, std::string>& params,
                                      const std::function<void(const std::string&)>& warn,
                                      const std::filesystem::path& asset_root = {});

}  // namespace wavetrace
