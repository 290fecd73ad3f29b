/* A host source outside any layer folder (must be reported). */
