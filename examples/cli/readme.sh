dampbound --version
dampbound bounds two-node --gamma 0.002
dampbound run two-node --gamma 0.002
dampbound run two-node --gamma 0.0005 --policy clamp
dampbound suggest two-node --dt 0.05
