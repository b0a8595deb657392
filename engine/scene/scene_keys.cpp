#include "engine/scene/scene_keys.hpp"

#include <charconv>
#include <cstdint>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "engine/types.hpp"

namespace drumlab {
std::vector<std::string> split_text(const std::string& text, char by) {
  std::vector<std::string> out;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, by);) out.push_back(part);
  return out;
}

namespace {

template <class T>
bool parse_number(const std::string& text, T& value) {
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  return ec == std::errc() && ptr == end;
}

}  // namespace

void set_scene_key(toml::table& root, const std::string& key, const std::string& text,
                   const std::string& context) {
  toml::table* table = &root;
  const std::vector<std::string> path = split_text(key, '.');
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    toml::node* next = table->get(path[k]);
    if (next == nullptr) next = &table->insert(path[k], toml::table{}).first->second;
    table = next->as_table();
    if (table == nullptr) {
      throw InputError(fmt::format("{}: '{}' is not a table in the scene", context, path[k]));
    }
  }
  const std::string& leaf = path.back();
  const toml::node* old = table->get(leaf);
  std::int64_t i = 0;
  double d = 0.0;
  const auto bad = [&](const char* what) {
    return InputError(fmt::format("{}: '{}' is not {}", context, text, what));
  };
  if (old != nullptr && old->is_integer()) {
    if (!parse_number(text, i)) throw bad("a whole number");
    table->insert_or_assign(leaf, i);
  } else if (old != nullptr && old->is_floating_point()) {
    if (!parse_number(text, d)) throw bad("a number");
    table->insert_or_assign(leaf, d);
  } else if (old != nullptr && old->is_boolean()) {
    if (text != "true" && text != "false") throw bad("true or false");
    table->insert_or_assign(leaf, text == "true");
  } else if (old != nullptr && !old->is_string()) {
    throw InputError(fmt::format("{}: {} is an array or table, not a value", context, key));
  } else if (old == nullptr && parse_number(text, i)) {
    table->insert_or_assign(leaf, i);
  } else if (old == nullptr && parse_number(text, d)) {
    table->insert_or_assign(leaf, d);
  } else if (old == nullptr && (text == "true" || text == "false")) {
    table->insert_or_assign(leaf, text == "true");
  } else {
    table->insert_or_assign(leaf, text);
  }
}

const toml::node* find_scene_key(const toml::table& root, const std::string& key) {
  const toml::node* node = &root;
  for (const std::string& part : split_text(key, '.')) {
    const toml::table* table = node->as_table();
    if (table == nullptr) return nullptr;
    node = table->get(part);
    if (node == nullptr) return nullptr;
  }
  return node;
}

toml::node* find_scene_key(toml::table& root, const std::string& key) {
  toml::table* table = &root;
  toml::node* node = nullptr;
  for (const std::string& part : split_text(key, '.')) {
    if (table == nullptr || (node = table->get(part)) == nullptr) return nullptr;
    table = node->as_table();
  }
  return node;
}

}  // namespace drumlab
