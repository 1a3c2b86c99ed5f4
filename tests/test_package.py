import contact
import glstat


def test_packages_import():
    assert glstat.__version__
    assert contact.Surface
