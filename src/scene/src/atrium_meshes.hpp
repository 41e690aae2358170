// Private: the atrium's architectural pieces, each built to a triangle budget.
#pragma once

#include "shapes.hpp"

namespace fgb::scene::atrium {

// Dimensions shared by the meshes and their placement (metres; X is the courtyard's long axis).
inline constexpr float kColumnSpacing = 3.5f;
inline constexpr float kArchRadius = kColumnSpacing / 2.0f;
inline constexpr float kGroundColumnHeight = 4.0f;
inline constexpr float kUpperColumnBase = 6.4f;
inline constexpr float kUpperColumnHeight = 3.2f;
inline constexpr float kArchRise = 2.0f;          // springing line to the top of the spandrel
inline constexpr float kArcadeZ = 6.0f;           // arcades at z = +-6
inline constexpr float kGalleryWallZ = 10.0f;     // gallery back walls at z = +-10
inline constexpr float kHalfLength = 16.0f;       // end walls at x = +-16
inline constexpr float kStoreyHeight = 6.0f;

MeshData column(const std::string& name, double budget, float height, float radius);
MeshData arch(const std::string& name, double budget, float depth);
MeshData wallPanel(const std::string& name, double budget, float width, float height, uint32_t seed);
MeshData cornice(const std::string& name, double budget, float length);
MeshData drape(const std::string& name, double budget, uint32_t seed);
MeshData plant(const std::string& name, double budget, uint32_t seed);
MeshData vase(const std::string& name, double budget);
MeshData lantern(const std::string& name, double budget);
MeshData brazier(const std::string& name, double budget);
MeshData floorGrid(const std::string& name, double budget);

}  // namespace fgb::scene::atrium
