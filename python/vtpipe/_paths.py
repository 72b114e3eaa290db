"""Where libvts-decode.so.0 is, relative to this package's directory. cmake --install and the
build tree write their own copy of this file; this one (the source tree's) finds nothing and
leaves the search to the loader (LD_LIBRARY_PATH, ldconfig)."""
DECODE_LIBRARY_DIR = "."
