"""The golden model's package: its public names."""


def test_package_reexports_public_api():
    import fastnms.golden as fastnms
    from fastnms.golden import fast, image, model, nms

    assert fastnms.detect is model.detect and fastnms.fast_maps is fast.fast_maps
    assert fastnms.nms_region is nms.nms_region and fastnms.load_grey is image.load_grey
    assert fastnms.SCORES == ("opencv", "sad")
    assert fastnms.NMS_MODES == ("none", "3x3", "region4", "region8")
    assert len(fastnms.CIRCLE_OFFSETS) == 16
