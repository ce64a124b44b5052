"""Fine-tuning a vision-language navigator on the training export (``vlln train sft``)."""
