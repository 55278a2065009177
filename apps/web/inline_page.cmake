# Puts the module's JavaScript (its wasm inside, base64) into the page where the shell says
# <!-- phonglab.js -->: one file that needs nothing beside it. THREADS, when given, is the
# threaded module's script and its worker's script: they go in as text (a type the browser does
# not run, "</script" and "<!--" escaped as JavaScript reads them the same), for the page to start
# from Blobs where it is cross-origin isolated.
file(READ ${SHELL} page)
file(READ ${SCRIPT} script)
set(threads "")
if(THREADS)
  list(GET THREADS 0 main_file)
  list(GET THREADS 1 worker_file)
  foreach(part main worker)
    file(READ ${${part}_file} text)
    string(REPLACE "</script" "<\\/script" text "${text}")
    string(REPLACE "<!--" "<\\!--" text "${text}")
    string(APPEND threads "<script type=\"text/plain\" id=\"phonglab-threads-${part}\">\n${text}\n</script>\n")
  endforeach()
endif()
string(REPLACE "<!-- phonglab.js -->" "${threads}<script>\n${script}\n</script>" page "${page}")
file(WRITE ${OUT} "${page}")
