// Debian installs lodepng.h at the top of the include path.
#pragma once
#include <lodepng.h>
