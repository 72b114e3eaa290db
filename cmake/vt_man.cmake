# Writes a man page (section 1) from a tool's --help, at build time:
#   cmake -DTOOL=<path of the executable> -DNAME=<tool name> -DVERSION=<x.y.z> -DOUT=<file.1> -P vt_man.cmake
# The help text is the page's body, verbatim (no-fill), with roff's special characters escaped;
# the NAME line takes the help's first sentence after the usage lines.
execute_process(COMMAND ${TOOL} --help OUTPUT_VARIABLE help RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${TOOL} --help failed (${rc})")
endif()
string(REPLACE "\\" "\\e" help "${help}")
string(REPLACE "\n." "\n\\&." help "${help}")
string(REPLACE "\n'" "\n\\&'" help "${help}")
# the summary: the first line that does not start with "usage:" or white space
string(REPLACE "\n" ";" lines "${help}")
set(summary "")
foreach(line IN LISTS lines)
  if(NOT line MATCHES "^(usage:| |\t|$)")
    set(summary "${line}")
    break()
  endif()
endforeach()
string(REGEX REPLACE "\\.$" "" summary "${summary}")
string(TOUPPER "${NAME}" upper)
file(WRITE ${OUT}.tmp
".TH ${upper} 1 \"\" \"vtpipe ${VERSION}\" \"vtpipe\"
.SH NAME
${NAME} \\- ${summary}
.SH SYNOPSIS AND OPTIONS
.nf
${help}.fi
.SH SEE ALSO
The page docs/cli/${NAME}.md of the vtpipe sources, and vt-atlas(1), vt-offset(1), vt-tiles(1),
vt-info(1), vt-convert(1), vt-merge(1), vt-export(1), vt-view(1).
")
file(RENAME ${OUT}.tmp ${OUT})
