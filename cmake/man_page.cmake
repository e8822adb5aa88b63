# Writes one gzipped man page from a tool's --help and --version with help2man (cmake -P).
#   -DTOOL=<executable> -DNAME=<tool name> -DSECTION=<1|8> -DHELP2MAN=<help2man> -DGZIP=<gzip>
#   -DOUTPUT=<file.N.gz>
# The page's NAME line is the first line of --help without its "prog: " prefix (docs/cli.md).
execute_process(COMMAND ${TOOL} --help OUTPUT_VARIABLE help RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${NAME} --help exited with ${status}")
endif()
string(REGEX MATCH "^[^\n]*" first_line "${help}")
string(REGEX REPLACE "^${NAME}: *" "" summary "${first_line}")
string(REGEX REPLACE "\\.$" "" summary "${summary}")
if(summary STREQUAL first_line OR summary STREQUAL "")
  message(FATAL_ERROR "${NAME} --help: the first line must be '${NAME}: what it does', "
                      "got '${first_line}'")
endif()
get_filename_component(out_dir ${OUTPUT} DIRECTORY)
string(REGEX REPLACE "\\.gz$" "" page ${OUTPUT})
execute_process(
  COMMAND ${HELP2MAN} --no-info --section=${SECTION} --name=${summary}
          --source=litamin2 --output=${page} ${TOOL}
  RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "help2man ${NAME} failed (${status})")
endif()
# -n: no name or time stamp in the gzip header, so the package is reproducible.
execute_process(COMMAND ${GZIP} -9nf ${page} RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "gzip ${page} failed (${status})")
endif()
