#pragma once
// The one way our code sees OpenGL: core 3.3 prototypes at compile time, no loader. The
// library that provides them is chosen when an executable links (libGL for the window,
// libOSMesa for headless runs and tests; see render/CMakeLists.txt). Include this before any
// other header that may pull in GL/gl.h (GLFW: define GLFW_INCLUDE_NONE).
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/gl.h>
#include <GL/glext.h>
