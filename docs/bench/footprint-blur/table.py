#!/usr/bin/env python3
"""The table of docs/bench/footprint-blur/README.md: per scene and technique, the prefiltered map's build and the
frame (GPU ms, median of the repeats) and the RMSE, before and after. Usage: table.py docs/bench/footprint-blur"""
import csv,sys
def load(d):
    out={}
    for r in csv.DictReader(open(d)):
        out[(r['scene'].split('/')[-2], r['technique'])]=r
    return out
stage={'vsm':'moment_map','esm':'moment_map','msm':'power_moment_map','convsm':'fourier_basis'}
print("| scene | technique | build before | after | frame before | after | RMSE before, after |")
print("| --- | --- | ---: | ---: | ---: | ---: | --- |")
for kind in ('heldout','datasets'):
    B=load(f'{sys.argv[1]}/before/{kind}.csv'); A=load(f'{sys.argv[1]}/after/{kind}.csv')
    for key in sorted(B):
        b,a=B[key],A[key]; s=stage[key[1]]
        print(f"| {key[0]} | `{key[1]}` | {float(b[s+'_gpu_ms']):.0f} ms | {float(a[s+'_gpu_ms']):.0f} ms | {float(b['frame_gpu_ms']):.0f} ms | {float(a['frame_gpu_ms']):.0f} ms | {float(b['rmse']):.6f}, {float(a['rmse']):.6f} |")
