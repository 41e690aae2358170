// The typed blackboard (Frostbite's, the thesis' "Context"): features publish the handles they
// produce under their own struct type and read what others published, without knowing each other.
#pragma once

#include <fgb/core/error.hpp>

#include <any>
#include <string>
#include <typeindex>
#include <unordered_map>
#include <utility>

namespace fgb::features {

class Blackboard {
 public:
  // Stores (or replaces) the entry of type T and returns it.
  template <class T>
  T& set(T value) {
    auto& slot = entries_[std::type_index(typeid(T))];
    slot = std::move(value);
    return std::any_cast<T&>(slot);
  }

  template <class T>
  [[nodiscard]] T* find() {
    const auto it = entries_.find(std::type_index(typeid(T)));
    return it == entries_.end() ? nullptr : std::any_cast<T>(&it->second);
  }
  template <class T>
  [[nodiscard]] const T* find() const {
    const auto it = entries_.find(std::type_index(typeid(T)));
    return it == entries_.end() ? nullptr : std::any_cast<T>(&it->second);
  }

  // The entry of type T; a missing entry is a wiring bug between features, reported by type name.
  template <class T>
  [[nodiscard]] T& get() {
    if (T* entry = find<T>()) return *entry;
    throw std::logic_error(std::string("blackboard has no entry of type ") + typeid(T).name());
  }
  template <class T>
  [[nodiscard]] const T& get() const {
    if (const T* entry = find<T>()) return *entry;
    throw std::logic_error(std::string("blackboard has no entry of type ") + typeid(T).name());
  }

  [[nodiscard]] bool empty() const { return entries_.empty(); }

 private:
  std::unordered_map<std::type_index, std::any> entries_;
};

}  // namespace fgb::features
