# Writes OUT (a C file defining sl_git_sha()) from the current git state, on
# every build, touching the file only when the SHA changed so nothing
# rebuilds needlessly. "-dirty" marks tracked files whose content differs
# from the commit.
#
# Two ways this used to say "-dirty" (or a wrong SHA) of a clean source:
#  - a source tree that is not itself a checkout (an exported or unpacked
#    tree) but lies inside another repository: git answered for that outer
#    repository, its SHA and its changes. Only a repository whose top level
#    is SRC itself is asked now; any other tree is "unknown".
#  - a tree copied without its file modes (a copy to another machine or
#    file system, an unpack under another umask): git counted the lost
#    executable bits as changes. Only content counts now (core.fileMode
#    off for this question), which is what the results depend on.
# --no-optional-locks: the question never writes the index, so a build
# running beside another git command cannot collide with it.
execute_process(COMMAND git rev-parse --show-toplevel WORKING_DIRECTORY ${SRC}
                OUTPUT_VARIABLE top OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE rc)
set(sha "unknown")
if(rc EQUAL 0 AND NOT top STREQUAL "")
  file(REAL_PATH "${top}" top_real)
  file(REAL_PATH "${SRC}" src_real)
  if(top_real STREQUAL src_real)
    execute_process(COMMAND git rev-parse --short=12 HEAD WORKING_DIRECTORY ${SRC}
                    OUTPUT_VARIABLE head OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE rc)
    if(rc EQUAL 0 AND NOT head STREQUAL "")
      set(sha "${head}")
      execute_process(COMMAND git --no-optional-locks -c core.fileMode=false status --porcelain
                              --untracked-files=no
                      WORKING_DIRECTORY ${SRC}
                      OUTPUT_VARIABLE dirty OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE rc)
      if(NOT rc EQUAL 0)
        set(sha "${head}-unknown-state")
      elseif(NOT dirty STREQUAL "")
        set(sha "${head}-dirty")
      endif()
    endif()
  endif()
endif()
set(text "/* generated at build time: do not edit */\nconst char *sl_git_sha(void) { return \"${sha}\"; }\n")
if(EXISTS ${OUT})
  file(READ ${OUT} old)
endif()
if(NOT "${old}" STREQUAL "${text}")
  file(WRITE ${OUT} "${text}")
endif()
