// Debian installs qoi.h at the top of the include path.
#pragma once
#include <qoi.h>
