// A shared library that is no lodbench plugin: it exports no lodbench_plugin() (tests/test_plugins.cpp).
extern "C" int notALodbenchPlugin() {
  return 42;
}
