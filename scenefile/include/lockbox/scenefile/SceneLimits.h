#pragma once
/// @file
/// Bounds that protect a loader from hostile scene files: each one is checked while the file is
/// read, before anything large is allocated, and exceeding it is an `e_limit` error naming the
/// bound. The defaults admit every R.U.B.E. level we know of by a wide margin (a 10,000-body
/// scene is about 3 MB and 300,000 JSON values).

#include <cstddef>

#include "lockbox/common/Settings.h"

namespace lockbox::scenefile {

/// Bounds applied while loading a scene file.
struct SceneLimits {
    size_t maxFileBytes = size_t{64} << 20;  ///< bytes of JSON text (64 MiB)
    int32 maxDepth = 32;                     ///< nesting of arrays and objects (the format needs 8; at most 256)
    uint32 maxValues = 8u << 20;             ///< JSON values of the whole file (about 32 bytes each in memory)
    int32 maxBodies = 200000;                ///< entries of "body"
    int32 maxFixtures = 1000000;             ///< fixtures of all bodies together
    int32 maxJoints = 200000;                ///< entries of "joint"
    int32 maxImages = 100000;                ///< entries of "image"
    int32 maxChainVertices = 100000;         ///< vertices of one chain or loop shape
    int32 maxImageValues = 1000000;          ///< numbers in one image's vertex, texture and index arrays
    int32 maxProperties = 10000;             ///< custom properties of one object
};

}  // namespace lockbox::scenefile
