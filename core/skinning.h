// Linear-blend skinning on the CPU (glTF 2.0 §3.7.3.3): each vertex of a skinned mesh moves
// with the weighted sum of its joints' skinning matrices, jointWorld x inverseBind.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "core/scene.h"

namespace photovr {

// The skin's matrices for world node transforms 'world' (indexed like Scene::nodes).
std::vector<glm::dmat4> skinningMatrices(const Skin& skin, const std::vector<glm::dmat4>& world);

// Writes the mesh's positions, normals and tangents from its bind pose (mesh.skinning):
// p = M p_bind and n = normalize(M^-T n_bind), t = normalize(M t_bind) with the blended
// M = sum_j w_j matrices[joint_j], in double, vertices in parallel. A vertex whose blended
// matrix flattens its normal to zero keeps its bind normal.
void skinMesh(Mesh& mesh, const std::vector<glm::dmat4>& matrices);

// The bind positions alone, skinned by 'matrices' into 'out' (the previous pose's).
void skinPositions(const MeshSkinning& skinning, const std::vector<glm::dmat4>& matrices,
                   std::vector<glm::vec3>& out);

}  // namespace photovr
