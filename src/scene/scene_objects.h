// The "objects" array of a scene: meshes (OBJ), Bezier patch sets, spheres and planes. Internal
// to load_scene, which has read the materials by then.
#pragma once

#include "scene/json_node.h"
#include "scene/scene.h"

namespace glint {

// Appends every object of `objects` to scene.meshes / spheres / planes. Files are relative to the
// folder of scene.file.
void read_objects(const scene_json::Node& objects, Scene& scene);

}  // namespace glint
