def pytest_configure(config):
    config.addinivalue_line("markers", "sanitize: also run against the ASan/UBSan build (sva_san)")
