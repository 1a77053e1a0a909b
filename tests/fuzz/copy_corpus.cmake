# cmake -DSRC=dir -DDST=dir -P copy_corpus.cmake: DST becomes a fresh copy of SRC.
file(REMOVE_RECURSE ${DST})
file(MAKE_DIRECTORY ${DST})
file(GLOB seeds ${SRC}/*)
file(COPY ${seeds} DESTINATION ${DST})
