# trn_doc_example(NAME OUT): writes the fenced code block that follows "<!-- example: NAME -->" in
# docs/EMBEDDING.md to OUT. Runs at configure time and again whenever the doc changes, so the tests
# compile exactly the text a reader sees.
function(trn_doc_example name out)
  set(doc ${PROJECT_SOURCE_DIR}/docs/EMBEDDING.md)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${doc})
  file(READ ${doc} text)
  string(FIND "${text}" "<!-- example: ${name} -->" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${doc}: no '<!-- example: ${name} -->' marker")
  endif()
  string(SUBSTRING "${text}" ${at} -1 text)
  string(FIND "${text}" "\n```" open)
  string(SUBSTRING "${text}" ${open} -1 text)
  string(SUBSTRING "${text}" 1 -1 text)  # past the newline before the fence
  string(FIND "${text}" "\n" eol)        # the rest of the fence line names the language
  math(EXPR eol "${eol} + 1")
  string(SUBSTRING "${text}" ${eol} -1 text)
  string(FIND "${text}" "\n```" close)
  if(close EQUAL -1)
    message(FATAL_ERROR "${doc}: the block of example ${name} is not closed")
  endif()
  string(SUBSTRING "${text}" 0 ${close} code)
  set(old "")
  if(EXISTS ${out})
    file(READ ${out} old)
  endif()
  if(NOT old STREQUAL "${code}\n")  # rewritten only when changed: no needless rebuilds
    file(WRITE ${out} "${code}\n")
  endif()
endfunction()
