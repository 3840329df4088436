# cgagen_generate(): run the cgagen tool on CluScript files at build time. (Filled in by the generator work.)
