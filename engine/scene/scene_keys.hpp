#pragma once
// A scene's TOML by dotted key (`liquid.surface_tension`), as `drumlab sweep --set` and the
// Python module's Scene write it: the value typed as the existing one, tables created where
// missing. Checking the scene is the loader's (parse_scene) afterwards.
#include <string>
#include <vector>

#include <toml++/toml.h>

namespace drumlab {

/// Sets `key` (dotted) in `root` to `text`, typed as the existing value is (else as the text
/// reads: integer, float, true/false, string). Throws InputError "CONTEXT: ..." for a path
/// through a value, a text that is not of the existing value's type, or an array or table there.
void set_scene_key(toml::table& root, const std::string& key, const std::string& text,
                   const std::string& context);

/// `text` cut at every `by` ("a.b.c" -> a, b, c; empty parts kept).
std::vector<std::string> split_text(const std::string& text, char by);

/// The node at `key` (dotted) in `root`, or nullptr.
const toml::node* find_scene_key(const toml::table& root, const std::string& key);
toml::node* find_scene_key(toml::table& root, const std::string& key);

}  // namespace drumlab
