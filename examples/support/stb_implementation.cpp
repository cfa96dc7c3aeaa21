// The one translation unit that compiles stb_image and stb_image_write (from Debian's
// libstb-dev). stb lives under /usr/include, so the compiler treats it as a system header
// and our -Werror flags do not apply to its code.
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
