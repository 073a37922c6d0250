// MOTIFMINE_API marks what the shared library libmotifmine exports; everything else in it is
// hidden (it is built with hidden visibility, its static parts with --exclude-libs).
#pragma once

#define MOTIFMINE_API [[gnu::visibility("default")]]
