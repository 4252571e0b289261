// grtrace/scene/object_ids.hpp
// How a pixel names what its ray ended on: a position in the scene, not a member of a closed list.
//   0  the sky (the ray escaped)
//   1  the horizon (the ray was captured)
//   2, 3, ...  the scene's own objects, in the order they were given to the scene (scene/scene.hpp)
// The "object" channel of a rendered image holds these numbers, and the image's "object_names" header
// attribute lists the names in the same order ("sky,horizon,disk,star-1,star-2"), so a reader never needs a
// table compiled into grtrace to know what "3" means. Adding an object edits nothing here.
#pragma once

namespace grtrace {

inline constexpr int kSkyObject = 0;           ///< escaped rays
inline constexpr int kHorizonObject = 1;       ///< captured rays
inline constexpr int kFirstSceneObject = 2;    ///< the first of the scene's own objects

}  // namespace grtrace
