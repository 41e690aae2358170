// The cluster LOD DAG of one mesh (cook.cpp): level-0 clusters of the mesh's triangles, then
// levels of simplified clusters, each made from a group of clusters of the levels below with the
// group's outer border locked (Karis 2021). See scene::Cluster for what each cluster stores.
#pragma once

#include <fgb/scene/scene.hpp>

namespace fgb::scene::detail {

// Appends the mesh's clusters, every level, to the scene's cluster arrays and sets the mesh's
// cluster range (level 0 first: Mesh::baseClusterCount). Needs the mesh's final index order.
void buildClusterLod(Scene& scene, Mesh& mesh);

}  // namespace fgb::scene::detail
