// Debian installs utf8proc.h at the top of the include path.
#pragma once
#include <utf8proc.h>
