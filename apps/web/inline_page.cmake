# Puts the module's JavaScript (its wasm inside, base64) into the page where the shell says
# <!-- phonglab.js -->: one file that needs nothing beside it.
file(READ ${SHELL} page)
file(READ ${SCRIPT} script)
string(REPLACE "<!-- phonglab.js -->" "<script>\n${script}\n</script>" page "${page}")
file(WRITE ${OUT} "${page}")
