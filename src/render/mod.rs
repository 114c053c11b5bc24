//! Rendering (SPEC 5 and 6): rays from the camera, intersections, shading.
